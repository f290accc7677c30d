//! Reading graph files: the text parsed into a [`GraphDocument`] (a file of another version is
//! refused by name, not as a syntax error) and brought to the current version by
//! [`crate::migrate`].

use crate::document::{FORMAT_VERSION, GraphDocument, Source, folder_of};
use crate::error::{ErrorKind, GraphError};
use serde::Deserialize;
use std::path::Path;

/// Only the version, read first so that a file of another version is reported as such and not
/// as a confusing syntax error.
#[derive(Deserialize)]
struct VersionProbe {
    version: u32,
}

impl GraphDocument {
    /// Parses graph text. `path` is only used in error messages.
    pub fn parse(text: &str, path: Option<&Path>) -> Result<(GraphDocument, Source), GraphError> {
        let source = Source {
            path: path.map(Path::to_path_buf),
            text: text.to_owned(),
        };
        let syntax = |e: ron::error::SpannedError| GraphError {
            file: source.path.clone(),
            position: Some((e.span.start.line, e.span.start.col)),
            kind: ErrorKind::Syntax {
                message: e.code.to_string(),
            },
            group: None,
        };
        let probe: VersionProbe = ron::from_str(text).map_err(syntax)?;
        if probe.version == 0 || probe.version > FORMAT_VERSION {
            let offset = text.find("version");
            return Err(source.error(
                offset,
                ErrorKind::UnsupportedVersion {
                    found: probe.version,
                    supported: FORMAT_VERSION,
                },
            ));
        }
        let doc: GraphDocument = ron::from_str(text).map_err(syntax)?;
        Ok((crate::migrate::to_current(doc), source))
    }

    /// Reads and parses a graph file.
    pub fn load(path: &Path) -> Result<(GraphDocument, Source), GraphError> {
        let text = std::fs::read_to_string(path).map_err(|e| GraphError {
            file: Some(path.to_path_buf()),
            position: None,
            kind: ErrorKind::Io {
                message: format!("cannot read graph file: {e}"),
            },
            group: None,
        })?;
        let (mut doc, source) = Self::parse(&text, Some(path))?;
        doc.base_dir = Some(folder_of(path));
        Ok((doc, source))
    }
}
