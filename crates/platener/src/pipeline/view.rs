//! Any step's snapshot as a 3D scene: the pipeline knows which snapshot each view draws.

use super::State;
use crate::scene::{self, Scene, SceneError, View};

impl State {
    /// `view` of this conversion as glTF binary (the web viewer's scenes, `platener scene`).
    pub fn scene(&self, view: View) -> Result<Scene, SceneError> {
        let need = |step: &'static str| SceneError::NotReached {
            view: view.name(),
            step,
        };
        match view {
            View::Model => scene::model(self.read.as_ref().ok_or_else(|| need("read"))?),
            View::Wireframe => scene::wireframe(self.mesh.as_ref().ok_or_else(|| need("mesh"))?),
            View::Coplanar => {
                let mesh = self.mesh.as_ref().ok_or_else(|| need("mesh"))?;
                let groups = self.coplanar.as_ref().ok_or_else(|| need("coplanar"))?;
                scene::coplanar(mesh, groups)
            }
            View::Primitives => {
                let mesh = self.mesh.as_ref().ok_or_else(|| need("mesh"))?;
                let classification = self.classify.as_ref().ok_or_else(|| need("classify"))?;
                scene::primitives(mesh, classification)
            }
            View::Plates => scene::plates(self.plates.as_ref().ok_or_else(|| need("plates"))?),
            View::Bent => scene::bent(
                self.plates.as_ref().ok_or_else(|| need("plates"))?,
                self.bends.as_deref(),
            ),
            View::Final => scene::assembly(&self.final_parts().as_ref().ok_or_else(|| need("parts"))?.parts),
        }
    }
}
