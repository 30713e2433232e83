//! The one builder of output paths: every file a run writes is named by a [`RelPath`],
//! whose parts are checked one by one, so that no name from a scene (its `name`, a chain's
//! dependent dimension, a joint, a driver, a measure, a position) can lead a file out of
//! the output directory. The scene's validation refuses such names first, at their field
//! ([`crate::scene::check_file_name`]); this is the check that holds whatever a later
//! kind forgets, and [`super::output`] checks again what it is given.

use std::fmt;

use crate::Error;

/// Most bytes of one part of a path (the common file systems' limit on a file name).
pub const MAX_PART_BYTES: usize = 255;

/// A file's path relative to the output directory, its parts joined with `/`, each a
/// plain file name: not empty, not `.` or `..`, not starting with `.` (hidden files, the
/// staging directories), no `/`, `\`, `:` or control character, at most
/// [`MAX_PART_BYTES`] bytes.
///
/// ```
/// use mechdraw::run::paths::RelPath;
/// let p = RelPath::join(&["diagrams", "shaper", "E.vx.svg"]).unwrap();
/// assert_eq!(p.as_str(), "diagrams/shaper/E.vx.svg");
/// assert!(RelPath::join(&["diagrams", "shaper", "../../x.svg"]).is_err());
/// assert!(RelPath::join(&["/etc/passwd"]).is_err());
/// ```
#[derive(Debug, Clone, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct RelPath(String);

impl RelPath {
    /// The path made of `parts`, each checked ([`RelPath`]); the error names the path and
    /// the part.
    pub fn join(parts: &[&str]) -> Result<RelPath, Error> {
        let path = parts.join("/");
        if parts.is_empty() {
            return Err(Error::OutputPath { path, message: "it has no part".into() });
        }
        for part in parts {
            if let Some(why) = part_problem(part) {
                return Err(Error::OutputPath {
                    path: crate::text::excerpt(&path),
                    message: format!("the part \"{}\" {why}", crate::text::excerpt(part)),
                });
            }
        }
        Ok(RelPath(path))
    }

    /// The path, `/`-separated.
    pub fn as_str(&self) -> &str {
        &self.0
    }
}

impl fmt::Display for RelPath {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.0)
    }
}

impl From<RelPath> for std::path::PathBuf {
    fn from(p: RelPath) -> std::path::PathBuf {
        std::path::PathBuf::from(p.0)
    }
}

impl From<RelPath> for String {
    fn from(p: RelPath) -> String {
        p.0
    }
}

/// Why `part` cannot be one part of an output path, if it cannot.
pub fn part_problem(part: &str) -> Option<&'static str> {
    if part.is_empty() {
        Some("is empty")
    } else if part == "." || part == ".." {
        Some("would leave its directory")
    } else if part.starts_with('.') {
        Some("starts with '.' (a hidden file)")
    } else if part.chars().any(|c| matches!(c, '/' | '\\' | ':') || c.is_control()) {
        Some("contains a separator ('/', '\\\\', ':') or a control character")
    } else if part.len() > MAX_PART_BYTES {
        Some("is longer than a file name can be (255 bytes)")
    } else {
        None
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_way_out_is_refused_by_name() {
        for bad in [
            &["..", "x.svg"][..],
            &["diagrams", "../../x-histogram.svg"],
            &["/abs.svg"],
            &["C:x.svg"],
            &["a\\..\\b.svg"],
            &["", "x"],
            &["frames", "."],
            &[".mechdraw-partial-1"],
            &["x\0.svg"],
            &[],
        ] {
            let e = RelPath::join(bad).unwrap_err();
            assert!(matches!(e, Error::OutputPath { .. }), "{bad:?}: {e}");
            assert_eq!(e.exit_code(), 2, "{bad:?}");
        }
        let long = "x".repeat(256);
        assert!(RelPath::join(&[&long]).unwrap_err().to_string().chars().count() < 400);
        assert_eq!(RelPath::join(&["frames", "a..b", "pos_000.svg"]).unwrap().as_str(), "frames/a..b/pos_000.svg");
    }
}
