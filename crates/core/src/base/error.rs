//! The one error type of agesim-core. Every variant names the file, line or value at fault,
//! so the app can print it as is.

use std::path::PathBuf;

/// Everything that can go wrong in agesim-core.
#[derive(Debug, thiserror::Error)]
pub enum Error {
    /// A file could not be read or written. The OS reason is part of the message and is
    /// deliberately not also exposed as [`std::error::Error::source`]: printers of error
    /// chains (anyhow's `{:#}`) would otherwise show it twice. Match the variant to
    /// inspect `cause` (e.g. its [`std::io::ErrorKind`]).
    #[error("{}: {cause}", path.display())]
    Io {
        path: PathBuf,
        cause: std::io::Error,
    },

    /// An image file could not be decoded or encoded.
    #[error("{}: {message}", path.display())]
    Image { path: PathBuf, message: String },

    /// A requested map size is 0 or larger than the maximum.
    #[error(
        "map size {width_px}×{height_px} is out of range: each side must be 1..={max_px} pixels"
    )]
    InvalidSize {
        width_px: u32,
        height_px: u32,
        max_px: u32,
    },

    /// The machine could not give the memory an operation needs.
    #[error("not enough memory for the {what}: it needs {} MiB", bytes / (1024 * 1024))]
    OutOfMemory { bytes: u64, what: &'static str },

    /// A parameter is outside its valid range.
    #[error("{what} = {value} is invalid: expected {expected}")]
    InvalidValue {
        what: String,
        value: String,
        expected: String,
    },

    /// A project file (`*.agesim.json`) or a `--set` edit is malformed, names an unknown
    /// field, or holds a value out of range; the message names the field (and its range).
    #[error("{source_name}: {message}")]
    Project {
        source_name: String,
        message: String,
    },
    /// A landmark file is malformed or names an unknown point; the message names the
    /// point at fault.
    #[error("{}: {message}", path.display())]
    Landmarks { path: PathBuf, message: String },

    /// The template could not be fitted to a head (too few landmarks, landmarks off the
    /// head); the message says which and what to do.
    #[error("fitting the template to the head: {message}")]
    Fit { message: String },

    /// A mesh file has an extension agesim cannot load.
    #[error("{}: unsupported mesh format \"{extension}\": expected .obj, .gltf or .glb", path.display())]
    UnsupportedMeshFormat { path: PathBuf, extension: String },

    /// A mesh file could not be parsed (the message comes from the OBJ or glTF reader,
    /// or names the mesh, primitive and attribute at fault).
    #[error("{}: {message}", path.display())]
    MeshFile { path: PathBuf, message: String },

    /// A mesh has no usable triangle left after cleaning.
    #[error("{source_name}: the mesh is empty: {reason}")]
    EmptyMesh { source_name: String, reason: String },

    /// An input file is larger than agesim reads (see [`crate::base::limits`]).
    #[error("{}: the file is larger than {} bytes, the limit for this kind of input", path.display(), limit_bytes)]
    TooLarge { path: PathBuf, limit_bytes: u64 },

    /// Several inputs of a project failed to load; each message names its file.
    #[error("{} inputs could not be loaded:\n{}", .0.len(), .0.join("\n"))]
    Inputs(Vec<String>),

    /// The caller cancelled the operation (a newer request replaced it); whatever the
    /// operation keeps (a [`crate::scene::Scene`]'s maps) is as it was before.
    #[error("cancelled")]
    Cancelled,

    /// A wrinkle description file has errors (all of them are listed).
    // Transparent: its text is the diagnostics' own, and it is not also exposed as a
    // source (error-chain printers would show it twice).
    #[error(transparent)]
    WrinkleFile(#[from] crate::base::diagnostic::ParseErrors),
}

impl Error {
    /// Wraps an I/O error with the path it happened on.
    pub fn io(path: impl Into<PathBuf>, cause: std::io::Error) -> Self {
        Self::Io {
            path: path.into(),
            cause,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_io_error_names_the_path_and_the_reason_exactly_once_in_its_chain() {
        let e = Error::io(
            "/no/such.obj",
            std::io::Error::new(std::io::ErrorKind::NotFound, "gone"),
        );
        assert_eq!(e.to_string(), "/no/such.obj: gone");
        // A chain printer (anyhow's `{:#}`) walks `source()`: nothing to repeat.
        assert!(std::error::Error::source(&e).is_none());
        assert!(
            matches!(e, Error::Io { ref cause, .. } if cause.kind() == std::io::ErrorKind::NotFound)
        );
    }
}
