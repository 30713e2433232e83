//! The crate's top-level error: one variant per layer, each carrying its context.

use crate::scene::SceneError;
use crate::solve::SolveError;

/// Anything `mechdraw run` or `check` can fail with.
#[derive(Debug, thiserror::Error)]
pub enum Error {
    /// Bad input: the scene file or a `--set` override.
    #[error(transparent)]
    Scene(#[from] SceneError),
    /// The scene is valid but the mechanism cannot be solved as asked (it cannot be
    /// assembled, a method fails); the message names where.
    #[error("{file}: {source}")]
    Solve {
        /// The scene file.
        file: String,
        /// What failed.
        source: SolveError,
    },
    /// A command-line option other than `--set` is malformed (e.g. `--drag`).
    #[error("{option}: {message}")]
    Option {
        /// The option as given.
        option: String,
        /// What is wrong and what would be valid.
        message: String,
    },
    /// A name would make an output path that is not a plain file inside the output
    /// directory (checked by [`crate::run::paths::RelPath`]). Example: a name `../x`.
    #[error(
        "cannot write `{path}`: {message}; a name that becomes part of a file name uses letters, digits, '-', '_' and '.', not starting with '.'"
    )]
    OutputPath {
        /// The path relative to the output directory (quoted short).
        path: String,
        /// Which part is wrong and why.
        message: String,
    },
    /// Writing an output failed.
    #[error("cannot write {path}: {source}")]
    Io {
        /// The file or directory.
        path: String,
        /// The I/O error.
        source: std::io::Error,
    },
    /// A number that is not finite (NaN, infinite) reached an output: the run writes nothing.
    /// Inputs whose results would overflow are refused at their field, so this names a
    /// quantity that is undefined where it was asked for. Example: a drawing text `inf N`.
    #[error("cannot write {what}: {at} is not a finite number (nothing was written)")]
    NonFinite {
        /// The file.
        what: String,
        /// Where in it (entity and layer, row and column, key path).
        at: String,
    },
    /// An output could not be produced (DXF or PNG encoding).
    #[error("cannot produce {what}: {message}")]
    Export {
        /// Which output.
        what: String,
        /// Why.
        message: String,
    },
}

impl Error {
    /// Process exit code: 2 for bad input (scene, options, unsolvable data), 1 for
    /// failures to write output.
    pub fn exit_code(&self) -> i32 {
        match self {
            Error::Scene(_) | Error::Solve { .. } | Error::Option { .. } | Error::OutputPath { .. } => 2,
            Error::Io { .. } | Error::Export { .. } | Error::NonFinite { .. } => 1,
        }
    }
}
