//! Scene kind `triad`: schema and validation. (Placeholder: filled in by the triad issue.)

use serde::Deserialize;

use super::{FieldError, Units};

/// The scene as written in the file (`kind` removed).
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawTriadScene {
    /// Output file stem.
    pub name: String,
    /// Length units.
    pub units: Units,
}

/// A checked `triad` scene.
#[derive(Debug, Clone)]
pub struct TriadScene {
    /// Output file stem.
    pub name: String,
    /// Length units.
    pub units: Units,
}

/// Validates the raw scene.
pub fn check(raw: RawTriadScene) -> Result<TriadScene, FieldError> {
    Ok(TriadScene { name: super::check_name(&raw.name)?, units: raw.units })
}
