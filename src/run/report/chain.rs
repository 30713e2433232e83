//! A chain scene's report (to come).

use super::{Frame, Gathered};
use crate::Error;
use crate::scene::chain::ChainScene;

/// The parts of a chain's report.
pub(super) fn gather<'a>(_scene: &'a ChainScene, _file: &str, _frame: Frame) -> Result<Gathered<'a>, Error> {
    Ok(Gathered { parts: Vec::new(), table: None, summary: serde_json::Value::Null, warnings: Vec::new() })
}
