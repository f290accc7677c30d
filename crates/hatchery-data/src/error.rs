//! The one error type of this crate.

use std::path::{Path, PathBuf};

/// Everything that can go wrong while loading or building data.
///
/// Every message is a single line and starts with the file path when there is one, so it can be
/// shown to a user as is (e.g. `brain.nii.gz: truncated gzip stream`).
#[derive(Debug, thiserror::Error)]
pub enum DataError {
    /// The file could not be opened or read.
    #[error("{}: {source}", path.display())]
    Io {
        path: PathBuf,
        source: std::io::Error,
    },
    /// The file is not valid for its format (corrupt, truncated, inconsistent).
    #[error("{}: {message}", path.display())]
    Format { path: PathBuf, message: String },
    /// The file claims more voxels than we are willing to allocate.
    #[error("{}: volume has {voxels} voxels, more than the limit of {limit}", path.display())]
    TooLarge {
        path: PathBuf,
        voxels: u64,
        limit: u64,
    },
    /// In-memory data that breaks an invariant, or parameter text that does not parse (a
    /// transfer function's points, a label list): no file involved.
    #[error("{0}")]
    Invalid(String),
    /// A valid file using a feature or format we do not read.
    #[error("{}: {message}", path.display())]
    Unsupported { path: PathBuf, message: String },
}

impl DataError {
    pub(crate) fn io(path: &Path, source: std::io::Error) -> Self {
        DataError::Io {
            path: path.to_path_buf(),
            source,
        }
    }

    /// A format error; the message is squeezed onto one line because some parsers we wrap
    /// produce multi-line messages.
    pub(crate) fn format(path: &Path, message: impl AsRef<str>) -> Self {
        DataError::Format {
            path: path.to_path_buf(),
            message: one_line(message.as_ref()),
        }
    }

    pub(crate) fn unsupported(path: &Path, message: impl AsRef<str>) -> Self {
        DataError::Unsupported {
            path: path.to_path_buf(),
            message: one_line(message.as_ref()),
        }
    }

    /// Attach a file path to an error that was produced without one (e.g. by `MeshData::new`).
    pub fn in_file(self, path: &Path) -> Self {
        match self {
            DataError::Invalid(message) => DataError::format(path, message),
            other => other,
        }
    }
}

/// A message about in-memory data or parameter text (no file involved) is [`DataError::Invalid`].
impl From<String> for DataError {
    fn from(message: String) -> Self {
        DataError::Invalid(message)
    }
}

impl From<&str> for DataError {
    fn from(message: &str) -> Self {
        DataError::Invalid(message.to_owned())
    }
}

/// Collapse whitespace runs (including newlines and tabs) to single spaces and cap the length.
pub(crate) fn one_line(s: &str) -> String {
    const MAX: usize = 300;
    let mut out = s.split_whitespace().collect::<Vec<_>>().join(" ");
    if out.len() > MAX {
        let mut cut = MAX;
        while !out.is_char_boundary(cut) {
            cut -= 1;
        }
        out.truncate(cut);
        out.push('…');
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn messages_are_one_line_and_name_the_file() {
        let e = DataError::format(Path::new("a/b.ply"), "Line 3:\n\tbad\r\n thing");
        assert_eq!(e.to_string(), "a/b.ply: Line 3: bad thing");
        let e = DataError::TooLarge {
            path: "x.nii".into(),
            voxels: 10,
            limit: 5,
        };
        assert_eq!(
            e.to_string(),
            "x.nii: volume has 10 voxels, more than the limit of 5"
        );
        let long = "x".repeat(1000);
        assert!(one_line(&long).chars().count() <= 301);
    }
}
