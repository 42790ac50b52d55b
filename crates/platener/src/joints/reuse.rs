//! Joints computed ahead of the `joints` step and handed on to it. The `bends` step computes
//! the joints of its layout to drop bent parts that would not hold together; when it drops
//! none, those are the joints the `joints` step would compute, so it takes them instead of
//! computing them a second time. They are taken only when made for the same plates, joint
//! settings and unjointed pairs, so reusing them never changes the output.

use std::collections::BTreeSet;

use platener_geom::GridError;

use super::{JointSettings, Joints, compute_except};
use crate::plates::Plate;

/// Joints computed for some plates, settings and bends, with the warnings they raised.
#[derive(Debug, Clone)]
pub struct Computed {
    made_for: CacheKey,
    /// The joints.
    pub joints: Joints,
    /// The warnings computing them raised, for the step that reports them.
    pub warnings: Vec<String>,
}

/// What joints were computed for: the plates (each one's thickness and area, exactly: the
/// plates snapshot they come from is never changed, only replaced), the settings, and the
/// plate pairs left without a joint.
#[derive(Debug, Clone, PartialEq)]
struct CacheKey {
    plates: Vec<(u64, u64)>,
    settings: JointSettings,
    unjointed: BTreeSet<(u32, u32)>,
}

impl CacheKey {
    fn new(plates: &[Plate], settings: &JointSettings, unjointed: &BTreeSet<(u32, u32)>) -> Self {
        Self {
            plates: plates
                .iter()
                .map(|p| (p.thickness.to_bits(), p.area.to_bits()))
                .collect(),
            settings: settings.clone(),
            unjointed: unjointed.clone(),
        }
    }
}

impl Computed {
    /// The joints of `plates` ([`compute_except`]), remembering what they were made for.
    pub fn compute(
        plates: &[Plate],
        settings: &JointSettings,
        unjointed: &BTreeSet<(u32, u32)>,
    ) -> Result<Self, GridError> {
        let (joints, warnings) = compute_except(plates, settings, unjointed)?;
        Ok(Self {
            made_for: CacheKey::new(plates, settings, unjointed),
            joints,
            warnings,
        })
    }

    /// Whether these are the joints [`compute_except`] gives for these arguments.
    pub fn made_for(&self, plates: &[Plate], settings: &JointSettings, unjointed: &BTreeSet<(u32, u32)>) -> bool {
        self.made_for == CacheKey::new(plates, settings, unjointed)
    }
}
