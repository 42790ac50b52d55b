//! Fabrication methods: the whole chain of steps from a model to a cutting plan.
//!
//! A method is a list of pipeline steps ending in a `parts` snapshot (the parts to cut and how
//! they connect), followed by the cutting-plan steps (`kerf`, `labels`, `sheets`, `export`),
//! which never need to know which method made the parts. The lists are the pipeline's
//! (`pipeline::StepId::of_method`); [`crate::convert`] runs them.
//!
//! | method | steps |
//! |---|---|
//! | plate | foundation, `plates`, `joints`, `parts` (plates with joints → parts) |
//! | stacked | foundation without welding, `stacked` (layers and shafts → parts) |
//! | interlocked | foundation without welding, `interlocked` (two families of upright slices in halved slots → parts) |
//! | classifier | read to mesh, `classify` (primitives → planar groups), then as plate, then `relief` (textures engraved) and `layers` (spheres and freeforms stacked among the plates) |

use serde::Serialize;

use crate::error::{Error, Result};
use crate::settings::{Settings, Weld};

/// The fabrication methods.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, PartialOrd, Ord)]
#[serde(rename_all = "lowercase")]
pub enum MethodKind {
    /// Flat plates joined by joints (the default).
    Plate,
    /// The model sliced into stacked layers joined by shafts.
    Stacked,
    /// Primitives found by RANSAC (planes, cylinders, cones) made into plates and bent
    /// parts: the plate method for textured and noisy models.
    Classifier,
    /// Two families of upright slices crossing at right angles in halved slots: organic
    /// models held together without glue.
    Interlocked,
}

impl MethodKind {
    /// Every method, in the order `--method all` runs them.
    pub const ALL: [MethodKind; 4] = [
        MethodKind::Plate,
        MethodKind::Stacked,
        MethodKind::Classifier,
        MethodKind::Interlocked,
    ];

    /// The name used in file names and reports.
    pub fn name(self) -> &'static str {
        match self {
            MethodKind::Plate => "plate",
            MethodKind::Stacked => "stacked",
            MethodKind::Classifier => "classifier",
            MethodKind::Interlocked => "interlocked",
        }
    }

    /// The settings this method runs with: the stacked method keeps every surface detail, and
    /// the classifier reads a texture's or noise's every vertex (welding a fine texture at a
    /// fraction of a sheet merges vertices across it and bends the faces around it), so both
    /// merge exact duplicates only.
    pub fn adjust(self, mut settings: Settings) -> Settings {
        if matches!(
            self,
            MethodKind::Stacked | MethodKind::Classifier | MethodKind::Interlocked
        ) {
            settings.weld = Weld::Off;
        }
        settings
    }
}

impl std::str::FromStr for MethodKind {
    type Err = Error;

    /// `plate`, `stacked`, `classifier` or `interlocked`.
    fn from_str(s: &str) -> Result<Self> {
        MethodKind::ALL
            .into_iter()
            .find(|m| m.name() == s.trim().to_ascii_lowercase())
            .ok_or_else(|| Error::Setting {
                name: "method",
                message: format!("{s:?} is none of plate, stacked, classifier, interlocked"),
            })
    }
}
