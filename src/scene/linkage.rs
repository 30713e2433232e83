//! Scene kind `linkage`: schema and validation. (Placeholder: filled in by the linkage issue.)

use serde::Deserialize;

use super::{FieldError, Units};

/// The scene as written in the file (`kind` removed).
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawLinkageScene {
    /// Output file stem.
    pub name: String,
    /// Length units.
    pub units: Units,
}

/// A checked `linkage` scene.
#[derive(Debug, Clone)]
pub struct LinkageScene {
    /// Output file stem.
    pub name: String,
    /// Length units.
    pub units: Units,
}

/// Validates the raw scene.
pub fn check(raw: RawLinkageScene) -> Result<LinkageScene, FieldError> {
    Ok(LinkageScene { name: super::check_name(&raw.name)?, units: raw.units })
}
