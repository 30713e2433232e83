//! The chain pipeline. (Placeholder: filled in by the chain issue.)

use super::{Outcome, RunOptions, solve_err};
use crate::Error;
use crate::scene::chain::ChainScene;
use crate::solve::chain::ChainError;

pub(super) fn run(_scene: &ChainScene, file: &str, _opts: &RunOptions) -> Result<Outcome, Error> {
    Err(solve_err(file)(ChainError::NotImplemented.into()))
}
