//! Writing an output file so that it is never seen half-written: every file the product writes
//! (graphs, recovery and layout files, pictures, SVG, npy, JSON, animations, manifests) goes
//! through [`write_atomically`].
//!
//! The new contents go to a temporary file in the target's own folder (a rename within one file
//! system is atomic), are flushed to disk, and the file is renamed over the target; then the
//! folder is flushed, so that the rename itself survives a crash. A render killed mid-write (a
//! batch worker pre-empted by Slurm, Ctrl+C) leaves the old file or none, never a truncated one
//! that looks done; a failing writer leaves no temporary file behind.

use std::fs::File;
use std::io::{self, Write};
use std::path::Path;

/// Writes `path` atomically with `write`, which gets the temporary file (Write + Seek, as
/// encoders such as PNG's want; buffer it yourself for many small writes).
///
/// Errors: creating the temporary file in `path`'s folder, `write`'s own error, flushing or
/// renaming; in every case `path` keeps its old contents (or stays absent).
pub fn write_atomically(
    path: &Path,
    write: impl FnOnce(&mut File) -> io::Result<()>,
) -> io::Result<()> {
    let dir = match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p,
        _ => Path::new("."),
    };
    let name = path
        .file_name()
        .map_or_else(|| "output".into(), |n| n.to_string_lossy().into_owned());
    // Hidden and named after the target, so that a folder listing during a write says whose it
    // is; removed when dropped unless persisted.
    let prefix = format!(".{name}.");
    let mut builder = tempfile::Builder::new();
    builder.prefix(&prefix).suffix(".part");
    let old_permissions = std::fs::metadata(path).ok().map(|m| m.permissions());
    #[cfg(unix)]
    {
        // A temporary file is made 0600, which would leave every figure unreadable to the
        // group: a new file gets what `File::create` gives (0666 less the umask).
        use std::os::unix::fs::PermissionsExt;
        builder.permissions(std::fs::Permissions::from_mode(0o666));
    }
    let mut tmp = builder.tempfile_in(dir)?;
    // A file written over keeps its permissions.
    if let Some(permissions) = old_permissions {
        tmp.as_file().set_permissions(permissions)?;
    }
    write(tmp.as_file_mut())?;
    tmp.as_file_mut().flush()?;
    tmp.as_file().sync_all()?;
    tmp.persist(path).map_err(|e| e.error)?;
    sync_folder(dir);
    Ok(())
}

/// [`write_atomically`] of a byte string.
pub fn write_bytes_atomically(path: &Path, bytes: &[u8]) -> io::Result<()> {
    write_atomically(path, |f| f.write_all(bytes))
}

/// Flushes a folder's entries (the rename) to disk. Not every platform opens folders as files
/// (Windows does not), and the rename is done either way, so a failure is not an error.
fn sync_folder(dir: &Path) {
    if let Ok(folder) = File::open(dir) {
        let _ = folder.sync_all();
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn entries(dir: &Path) -> Vec<String> {
        let mut names: Vec<String> = std::fs::read_dir(dir)
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .collect();
        names.sort();
        names
    }

    #[test]
    fn a_failing_writer_leaves_the_old_file_and_no_temporary() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("figure.png");
        write_bytes_atomically(&path, b"old contents").unwrap();
        let e = write_atomically(&path, |f| {
            f.write_all(b"half of the new")?;
            Err(io::Error::other("the encoder failed"))
        })
        .unwrap_err();
        assert_eq!(e.to_string(), "the encoder failed");
        assert_eq!(std::fs::read(&path).unwrap(), b"old contents");
        assert_eq!(entries(dir.path()), ["figure.png"]);
        write_bytes_atomically(&path, b"new contents").unwrap();
        assert_eq!(std::fs::read(&path).unwrap(), b"new contents");
        assert_eq!(entries(dir.path()), ["figure.png"]);
    }

    /// A new file gets the permissions `File::create` gives (not a temporary file's 0600); a
    /// file written over keeps its own.
    #[cfg(unix)]
    #[test]
    fn permissions_are_those_of_a_plain_write() {
        use std::os::unix::fs::PermissionsExt;
        let dir = tempfile::tempdir().unwrap();
        let mode = |p: &Path| std::fs::metadata(p).unwrap().permissions().mode() & 0o777;
        let plain = dir.path().join("plain.png");
        File::create(&plain).unwrap();
        let new = dir.path().join("new.png");
        write_bytes_atomically(&new, b"new").unwrap();
        assert_eq!(mode(&new), mode(&plain));
        let old = dir.path().join("old.png");
        std::fs::write(&old, b"old").unwrap();
        std::fs::set_permissions(&old, std::fs::Permissions::from_mode(0o640)).unwrap();
        write_bytes_atomically(&old, b"replaced").unwrap();
        assert_eq!(mode(&old), 0o640);
        assert_eq!(std::fs::read(&old).unwrap(), b"replaced");
    }

    #[test]
    fn a_missing_folder_is_an_error() {
        let dir = tempfile::tempdir().unwrap();
        assert!(write_bytes_atomically(&dir.path().join("no/such/x.png"), b"x").is_err());
        assert!(!dir.path().join("no").exists());
    }
}
