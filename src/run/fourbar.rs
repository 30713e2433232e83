//! The fourbar pipeline. (Placeholder until the drawing side lands: solves the motion and
//! reports it, writes nothing.)

use super::{Outcome, RunOptions, solve_err};
use crate::Error;
use crate::scene::fourbar::FourbarScene;
use crate::solve::fourbar::solve_motion;

pub(super) fn run(scene: &FourbarScene, file: &str, _opts: &RunOptions) -> Result<Outcome, Error> {
    let motion = solve_motion(&scene.spec).map_err(|e| solve_err(file)(e.into()))?;
    Ok(Outcome {
        summary: serde_json::json!({ "kind": "fourbar", "name": scene.name, "positions": motion.positions.len() }),
        report: format!("{}: {} positions solved", scene.name, motion.positions.len()),
        warnings: motion.warnings(),
        written: Vec::new(),
    })
}
