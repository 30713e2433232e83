//! Scene kind `chain`: schema and validation. (Placeholder: filled in by the chain issue.)

use serde::Deserialize;

use super::{FieldError, Units};

/// The scene as written in the file (`kind` removed).
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawChainScene {
    /// Output file stem.
    pub name: String,
    /// Length units.
    pub units: Units,
}

/// A checked `chain` scene.
#[derive(Debug, Clone)]
pub struct ChainScene {
    /// Output file stem.
    pub name: String,
    /// Length units.
    pub units: Units,
}

/// Validates the raw scene.
pub fn check(raw: RawChainScene) -> Result<ChainScene, FieldError> {
    Ok(ChainScene { name: super::check_name(&raw.name)?, units: raw.units })
}
