//! Step `parts` of the plate method: plates become parts to cut.
//!
//! Each plate is one part, numbered from 1 in plate order. (The joint steps, when they run,
//! change the plates' outlines and add the connections; this step only carries the result.)

use std::collections::BTreeMap;
use std::sync::Arc;

use crate::error::Result;
use crate::pipeline::{State, Step, StepContext, need};
use crate::plan::{Method, Part, PlanInput, SettingValue, SourceInfo};

/// The plan's description of the model.
pub fn source_info(state: &State) -> Result<SourceInfo> {
    let model = need(&state.read, "parts", "read")?;
    Ok(SourceInfo {
        name: model.name.clone(),
        triangles: model.triangles.len() as u64,
        bbox_min: model.bounds.min,
        bbox_max: model.bounds.max,
    })
}

/// Step `parts` (plate method).
pub struct PlatePartsStep;

impl Step for PlatePartsStep {
    fn name(&self) -> &'static str {
        "parts"
    }

    fn run(&self, state: &mut State, _cx: &mut StepContext<'_>) -> Result<()> {
        let plates = need(&state.plates, self.name(), "plates")?;
        let parts: Vec<Part> = plates
            .plates
            .iter()
            .enumerate()
            .map(|(i, p)| Part::plate(i as u32 + 1, p.thickness, p.polygon.clone(), p.frame))
            .collect();
        let s = &state.settings;
        let mut method_settings = BTreeMap::new();
        method_settings.insert("thicknesses".to_string(), SettingValue::Numbers(s.thicknesses.clone()));
        method_settings.insert(
            "weld".to_string(),
            SettingValue::Number(need(&state.weld, self.name(), "weld")?.distance),
        );
        method_settings.insert(
            "extruded_plates".to_string(),
            SettingValue::Flag(s.plates.mode == crate::PlateMode::InherentAndExtruded),
        );
        let mut input = PlanInput::new(source_info(state)?, Method::Plate, parts, Vec::new());
        input.settings = s.cut.clone();
        input.method_settings = method_settings;
        state.parts = Some(Arc::new(input));
        Ok(())
    }
}
