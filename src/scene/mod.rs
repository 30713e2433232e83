//! Scene files: the TOML a user writes, read into checked types.
//!
//! Loading is three steps, each with its own error: the text is parsed as TOML
//! ([`SceneError::Syntax`], with line and column); `--set` overrides are applied to the
//! parsed table ([`Override`]); the table is read into the scene kind's schema with unknown
//! fields refused and then validated ([`SceneError::Field`], naming the field path, what is
//! wrong and what would be valid). A scene that loads is safe to solve: no NaN, no
//! non-positive length reaches a solver.

pub mod chain;
pub mod fourbar;
pub mod linkage;
mod overrides;
pub mod synthesis;
pub mod tolerance;
pub mod triad;

use std::path::PathBuf;

use serde::de::DeserializeOwned;

pub use overrides::Override;

/// The scene kinds, as written in the `kind` field.
pub const KINDS: &[&str] = &["triad", "fourbar", "linkage", "chain", "synthesis"];

/// A loaded, validated scene.
#[derive(Debug, Clone)]
pub enum Scene {
    /// `kind = "triad"`: a 6R triad (seed 000).
    Triad(triad::TriadScene),
    /// `kind = "fourbar"`: a crank-rocker four-bar with a ternary coupler (seed 003).
    Fourbar(fourbar::FourbarScene),
    /// `kind = "linkage"`: a general planar linkage of bodies and joints (seed 002).
    Linkage(linkage::LinkageScene),
    /// `kind = "chain"`: a dimensional chain (seed 001).
    Chain(chain::ChainScene),
    /// `kind = "synthesis"`: a requirement; the run designs the mechanism that meets it.
    Synthesis(synthesis::SynthesisScene),
}

impl Scene {
    /// The `kind` string.
    pub fn kind(&self) -> &'static str {
        match self {
            Scene::Triad(_) => "triad",
            Scene::Fourbar(_) => "fourbar",
            Scene::Linkage(_) => "linkage",
            Scene::Chain(_) => "chain",
            Scene::Synthesis(_) => "synthesis",
        }
    }

    /// The scene's `name`, used for output file names.
    pub fn name(&self) -> &str {
        match self {
            Scene::Triad(s) => &s.name,
            Scene::Fourbar(s) => &s.name,
            Scene::Linkage(s) => &s.name,
            Scene::Chain(s) => &s.name,
            Scene::Synthesis(s) => &s.name,
        }
    }
}

/// A scene together with the file it came from.
#[derive(Debug, Clone)]
pub struct Loaded {
    /// The scene file as given on the command line (for messages).
    pub path: PathBuf,
    /// The checked scene.
    pub scene: Scene,
    /// The scene file's text as read (before any `--set`): the live page carries it.
    pub text: String,
}

/// `[frames]`: how an animation's frames are drawn.
#[derive(Debug, Clone, Default, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawFrames {
    /// `"per-frame"` (the default) or `"fixed"`.
    pub scales: Option<String>,
}

/// How the frames' polygon scales are chosen (`[frames] scales`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum FrameScales {
    /// Each frame's polygons at their own nice scale, each filling half to all of its panel,
    /// kept from frame to frame while it does (`"per-frame"`, the default).
    #[default]
    PerFrame,
    /// One scale per polygon for the whole run (`"fixed"`).
    Fixed,
}

/// `[frames]`, checked.
pub fn check_frames(raw: Option<&RawFrames>) -> Result<FrameScales, FieldError> {
    match raw.and_then(|f| f.scales.as_deref()) {
        None | Some("per-frame") => Ok(FrameScales::PerFrame),
        Some("fixed") => Ok(FrameScales::Fixed),
        Some(other) => Err(FieldError::new(
            "frames.scales",
            format!(
                "`{other}` is not a choice: \"per-frame\" (each frame's polygons at their own nice scale, the \
                 default) or \"fixed\" (one scale per polygon for the whole run)"
            ),
        )),
    }
}

/// Length units of a scene, stated once per file.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Deserialize, serde::Serialize)]
pub enum Units {
    /// Millimetres (and seconds, newtons): `units = "mm"`.
    #[serde(rename = "mm")]
    Mm,
    /// SI: metres, seconds, kilograms, newtons: `units = "SI"` (or `"m"`).
    #[serde(rename = "SI", alias = "m", alias = "si")]
    Si,
}

impl Units {
    /// Unit symbol for lengths.
    pub fn length(self) -> &'static str {
        match self {
            Units::Mm => "mm",
            Units::Si => "m",
        }
    }
}

/// What is wrong with a scene file or a `--set` override.
#[derive(Debug, thiserror::Error)]
pub enum SceneError {
    /// The file cannot be read. Example: a misspelt path.
    #[error("{file}: cannot read the scene file: {source}")]
    Read {
        /// The file.
        file: String,
        /// The I/O error.
        source: std::io::Error,
    },
    /// The text is not TOML. Example: `l12 = 50,0`.
    #[error("{file}: not valid TOML: {message}")]
    Syntax {
        /// The file.
        file: String,
        /// The TOML parser's message, with line and column.
        message: String,
    },
    /// No `kind`, or one that is not a scene kind. Example: `kind = "tirad"`.
    #[error("{file}: field `kind`: {message}; valid kinds: triad, fourbar, linkage, chain, synthesis")]
    Kind {
        /// The file.
        file: String,
        /// What is wrong.
        message: String,
    },
    /// A field is missing, unknown, of the wrong type, or has an invalid value.
    /// Example: `l12 = -5.0` ("must be a positive length").
    #[error("{file}: field `{}`: {message}", crate::text::excerpt(.field))]
    Field {
        /// The file.
        file: String,
        /// Dotted path of the field, e.g. `pattern.tol` or `r[2]`.
        field: String,
        /// What is wrong and what would be valid.
        message: String,
    },
    /// A `--set KEY=VALUE` override is malformed. Example: `--set l12`.
    #[error("--set {}: {message}", crate::text::excerpt(.spec))]
    Override {
        /// The override as given.
        spec: String,
        /// What is wrong.
        message: String,
    },
}

/// A field-level problem found by a kind's validation, before the file name is attached.
#[derive(Debug, Clone, PartialEq)]
pub struct FieldError {
    /// Dotted path of the field.
    pub field: String,
    /// What is wrong and what would be valid.
    pub message: String,
}

impl FieldError {
    /// A field error.
    pub fn new(field: impl Into<String>, message: impl Into<String>) -> FieldError {
        FieldError { field: field.into(), message: message.into() }
    }

    fn in_file(self, file: &str) -> SceneError {
        SceneError::Field { file: file.to_string(), field: self.field, message: self.message }
    }
}

/// Largest magnitude of a coordinate, a length or a tolerance, in the scene's unit (mm or
/// m). Beyond it a number is finite but meaningless (a thousand times the distance to the
/// Sun in metres), and products of such numbers overflow.
pub const MAX_LENGTH: f64 = 1e15;
/// Largest mass, kg.
pub const MAX_MASS_KG: f64 = 1e30;
/// Largest moment of inertia, kg·m² ([`MAX_MASS_KG`] at [`MAX_LENGTH`] metres).
pub const MAX_INERTIA_KG_M2: f64 = 1e60;
/// Largest force, N.
pub const MAX_FORCE_N: f64 = 1e30;
/// Largest torque, N·m.
pub const MAX_TORQUE_N_M: f64 = 1e45;
/// Largest angular speed, rad/s (about ten million revolutions a minute).
pub const MAX_ANGULAR_SPEED: f64 = 1e6;
/// Largest angular acceleration, rad/s².
pub const MAX_ANGULAR_ACCELERATION: f64 = 1e12;
/// Largest gravitational acceleration, m/s².
pub const MAX_GRAVITY: f64 = 1e12;
/// Largest magnitude of an angle written in degrees (a few thousand turns).
pub const MAX_ANGLE_DEG: f64 = 1e6;
/// Largest magnitude of a time, s.
pub const MAX_TIME_S: f64 = 1e9;

// With every input within these ranges the largest products stay far inside f64: an inertia
// force m·ω²·l ≤ 1e30·1e12·1e15 = 1e57 N, its moment 1e72 N·m, its square 1e144.

/// Checks that a scene field is a finite number of magnitude at most `max`; `what` says
/// what it is (`"an angular speed in rad/s"`).
pub fn within(field: &str, v: f64, max: f64, what: &str) -> Result<f64, FieldError> {
    if v.is_finite() && v.abs() <= max {
        Ok(v)
    } else {
        Err(FieldError::new(field, format!("must be {what} from -{max:e} to {max:e}, got {v:?}")))
    }
}

/// Checks that a scene field is a number from 0 to `max` (a mass, an inertia, a tolerance).
pub fn non_negative_within(field: &str, v: f64, max: f64, what: &str) -> Result<f64, FieldError> {
    if v.is_finite() && (0.0..=max).contains(&v) {
        Ok(v)
    } else {
        Err(FieldError::new(field, format!("must be {what} ≥ 0 and at most {max:e}, got {v:?}")))
    }
}

/// Checks that a pair field (a force, a gravity vector) has both components within ±`max`.
pub fn pair_within(field: &str, p: [f64; 2], max: f64, what: &str) -> Result<crate::geom::Vector, FieldError> {
    if p.iter().all(|v| v.is_finite() && v.abs() <= max) {
        Ok(crate::geom::Vector::new(p[0], p[1]))
    } else {
        Err(FieldError::new(field, format!("must be {what} [x, y], each from -{max:e} to {max:e}, got {p:?}")))
    }
}

/// Checks that a scene field is a finite, strictly positive length of at most
/// [`MAX_LENGTH`].
pub fn positive(field: &str, v: f64) -> Result<f64, FieldError> {
    if v.is_finite() && v > 0.0 && v <= MAX_LENGTH {
        Ok(v)
    } else {
        Err(FieldError::new(
            field,
            format!("must be a positive length of at most {MAX_LENGTH:e} (the scene's unit), got {v:?}"),
        ))
    }
}

/// Checks that a scene field is a finite number.
pub fn finite(field: &str, v: f64) -> Result<f64, FieldError> {
    if v.is_finite() { Ok(v) } else { Err(FieldError::new(field, format!("must be a finite number, got {v}"))) }
}

/// Checks that a scene field is a coordinate or a signed length: within ±[`MAX_LENGTH`].
pub fn length(field: &str, v: f64) -> Result<f64, FieldError> {
    within(field, v, MAX_LENGTH, "a length in the scene's unit")
}

/// Checks that a scene field is an angle in degrees: within ±[`MAX_ANGLE_DEG`].
pub fn angle_deg(field: &str, v: f64) -> Result<f64, FieldError> {
    within(field, v, MAX_ANGLE_DEG, "an angle in degrees")
}

/// Checks that a point field has finite coordinates within ±[`MAX_LENGTH`].
pub fn finite_point(field: &str, p: [f64; 2]) -> Result<crate::geom::Point, FieldError> {
    if p.iter().all(|v| v.is_finite() && v.abs() <= MAX_LENGTH) {
        Ok(crate::geom::Point::new(p[0], p[1]))
    } else {
        Err(FieldError::new(
            field,
            format!(
                "must be a point [x, y] of finite numbers, each from -{MAX_LENGTH:e} to {MAX_LENGTH:e} (the scene's unit), got {p:?}"
            ),
        ))
    }
}

/// Reads and checks the scene file `path`, with `overrides` applied in order (the file
/// system: feature `cli`; the core takes the text, [`parse`]).
#[cfg(feature = "cli")]
pub fn load(path: &std::path::Path, overrides: &[Override]) -> Result<Loaded, SceneError> {
    load_with(path, overrides, linkage::Redundancy::Refused)
}

/// [`load`], with a linkage's redundant link accepted or not ([`linkage::Redundancy`]:
/// `mechdraw report` accepts it to draw the structure).
#[cfg(feature = "cli")]
pub fn load_with(
    path: &std::path::Path,
    overrides: &[Override],
    redundancy: linkage::Redundancy,
) -> Result<Loaded, SceneError> {
    let file = path.display().to_string();
    let text = std::fs::read_to_string(path).map_err(|source| SceneError::Read { file: file.clone(), source })?;
    let scene = parse_with(&text, &file, overrides, redundancy)?;
    Ok(Loaded { path: path.to_path_buf(), scene, text })
}

/// Parses and checks scene text; `file` names it in messages.
pub fn parse(text: &str, file: &str, overrides: &[Override]) -> Result<Scene, SceneError> {
    parse_with(text, file, overrides, linkage::Redundancy::Refused)
}

/// [`parse`], with a linkage's redundant link accepted or not.
pub fn parse_with(
    text: &str,
    file: &str,
    overrides: &[Override],
    redundancy: linkage::Redundancy,
) -> Result<Scene, SceneError> {
    let mut table: toml::Table = text.parse().map_err(|e: toml::de::Error| SceneError::Syntax {
        file: file.to_string(),
        // The parser quotes the offending line: a megabyte-long one is cut.
        message: e.to_string().trim_end().lines().map(crate::text::excerpt).collect::<Vec<_>>().join("\n"),
    })?;
    for o in overrides {
        o.apply(&mut table)?;
    }
    let kind = match table.remove("kind") {
        None => {
            return Err(SceneError::Kind {
                file: file.to_string(),
                message: "missing (it must come first in the file)".into(),
            });
        }
        Some(toml::Value::String(k)) => k,
        Some(v) => {
            return Err(SceneError::Kind { file: file.to_string(), message: format!("must be a string, got {v}") });
        }
    };
    let checked = match kind.as_str() {
        "triad" => triad::check(read(table, file)?).map(Scene::Triad),
        "fourbar" => fourbar::check(read(table, file)?).map(Scene::Fourbar),
        "linkage" => linkage::check_with(read(table, file)?, redundancy).map(Scene::Linkage),
        "chain" => chain::check(read(table, file)?).map(Scene::Chain),
        "synthesis" => return synthesis::check(table, file).map(Scene::Synthesis),
        other => {
            return Err(SceneError::Kind {
                file: file.to_string(),
                message: format!("\"{other}\" is not a scene kind"),
            });
        }
    };
    checked.map_err(|e| e.in_file(file))
}

/// Deserialises a kind's raw schema from the table, naming the field on error.
fn read<T: DeserializeOwned>(table: toml::Table, file: &str) -> Result<T, SceneError> {
    serde_path_to_error::deserialize(table).map_err(|e| {
        let path = e.path().to_string();
        let inner = e.into_inner();
        let message = plain_message(inner.message().trim_end());
        // serde names the parent for unknown and missing fields: say which field exactly.
        let field = if path == "." { String::new() } else { path };
        let (field, message) = match unknown_or_missing(&message) {
            Some(name) if field.is_empty() => (name.to_string(), message),
            Some(name) if field != name && !field.ends_with(&format!(".{name}")) => {
                (format!("{field}.{name}"), message)
            }
            _ => (field, message),
        };
        SceneError::Field {
            file: file.to_string(),
            field: if field.is_empty() { "(top level)".into() } else { field },
            message,
        }
    })
}

/// serde's message in the words of the scene file: `expected usize` (or u32, u64) becomes
/// "a whole number (0, 1, 2, …)", `expected f64` "a number"; a long value it quotes is cut
/// to [`crate::text::QUOTE_CHARS`] characters.
fn plain_message(message: &str) -> String {
    let (head, expected) = match message.rsplit_once(", expected ") {
        Some((head, expected)) => (head, Some(expected)),
        None => (message, None),
    };
    let head =
        if head.chars().count() > 2 * crate::text::QUOTE_CHARS { crate::text::excerpt(head) } else { head.into() };
    let Some(expected) = expected else { return head };
    let plain = match expected {
        "usize" | "u64" | "u32" | "u16" | "u8" => "a whole number (0, 1, 2, …)",
        "isize" | "i64" | "i32" | "i16" | "i8" => "a whole number",
        "f64" | "f32" => "a number (e.g. 2.5; nan and inf are not numbers here)",
        "a boolean" => "true or false",
        other => other,
    };
    format!("{head}, expected {plain}")
}

/// The field name in serde's "unknown field `x`" / "missing field `x`" messages.
fn unknown_or_missing(message: &str) -> Option<&str> {
    for prefix in ["unknown field `", "missing field `"] {
        if let Some(rest) = message.strip_prefix(prefix) {
            return rest.split('`').next();
        }
    }
    None
}

/// Most characters of a name that becomes part of a file name.
pub const MAX_NAME_CHARS: usize = 100;

/// Whether `name` can be part of an output file name: 1 to [`MAX_NAME_CHARS`] ASCII
/// letters, digits, `-`, `_` and `.`, not starting with `.` (so never `.`, `..`, a hidden
/// file, a separator or a drive).
pub fn is_file_name(name: &str) -> bool {
    !name.is_empty()
        && name.len() <= MAX_NAME_CHARS
        && name.chars().all(|c| c.is_ascii_alphanumeric() || "-_.".contains(c))
        && !name.starts_with('.')
}

/// Checks a name that becomes part of output file names (the scene's `name`, a chain's
/// dependent dimension, a joint or a driver of a linkage): see [`is_file_name`]. The
/// message quotes at most [`crate::text::QUOTE_CHARS`] characters of it.
pub fn check_file_name(field: &str, name: &str) -> Result<String, FieldError> {
    if is_file_name(name) {
        return Ok(name.to_string());
    }
    Err(FieldError::new(
        field,
        format!(
            "\"{}\" cannot be part of a file name: use 1 to {MAX_NAME_CHARS} letters, digits, '-', '_' and '.', not starting with '.'",
            crate::text::excerpt(name)
        ),
    ))
}

/// Checks a scene `name`: it becomes a file stem, so it must be a plain file name
/// ([`check_file_name`]).
pub fn check_name(name: &str) -> Result<String, FieldError> {
    check_file_name("name", name)
}
