//! The fourbar pipeline. (Placeholder: filled in by the fourbar issue.)

use super::{Outcome, RunOptions, solve_err};
use crate::Error;
use crate::scene::fourbar::FourbarScene;
use crate::solve::fourbar::FourbarError;

pub(super) fn run(_scene: &FourbarScene, file: &str, _opts: &RunOptions) -> Result<Outcome, Error> {
    Err(solve_err(file)(FourbarError::NotImplemented.into()))
}
