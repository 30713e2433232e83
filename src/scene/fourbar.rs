//! Scene kind `fourbar`: schema and validation. (Placeholder: filled in by the fourbar issue.)

use serde::Deserialize;

use super::{FieldError, Units};

/// The scene as written in the file (`kind` removed).
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawFourbarScene {
    /// Output file stem.
    pub name: String,
    /// Length units.
    pub units: Units,
}

/// A checked `fourbar` scene.
#[derive(Debug, Clone)]
pub struct FourbarScene {
    /// Output file stem.
    pub name: String,
    /// Length units.
    pub units: Units,
}

/// Validates the raw scene.
pub fn check(raw: RawFourbarScene) -> Result<FourbarScene, FieldError> {
    Ok(FourbarScene { name: super::check_name(&raw.name)?, units: raw.units })
}
