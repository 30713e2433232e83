//! The linkage pipeline. (Placeholder: filled in by the linkage issue.)

use super::{Outcome, RunOptions, solve_err};
use crate::Error;
use crate::scene::linkage::LinkageScene;
use crate::solve::linkage::LinkageError;

pub(super) fn run(_scene: &LinkageScene, file: &str, _opts: &RunOptions) -> Result<Outcome, Error> {
    Err(solve_err(file)(LinkageError::Drag { what: "todo".into() }.into()))
}
