//! The triad pipeline. (Placeholder: filled in by the triad issue.)

use super::{Outcome, RunOptions, solve_err};
use crate::Error;
use crate::scene::triad::TriadScene;
use crate::solve::triad::TriadError;

pub(super) fn run(_scene: &TriadScene, file: &str, _opts: &RunOptions) -> Result<Outcome, Error> {
    Err(solve_err(file)(TriadError::Movable.into()))
}
