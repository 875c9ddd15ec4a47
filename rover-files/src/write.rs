//! Writing: regular files inside the folder given, never through a link.

use std::fs::File;
use std::io::{self, Write};
use std::path::{Path, PathBuf};

use crate::read::kind_of;

/// An output folder: created if missing, refused if it is something else.
/// Files are written into it by name only.
#[derive(Clone, Debug)]
pub struct OutputDir {
    root: PathBuf,
}

impl OutputDir {
    /// The folder `path`, created with its parents if missing. A path that
    /// exists and is not a folder (a file, a device, a FIFO) is refused: it
    /// is never replaced.
    pub fn create(path: &Path) -> io::Result<Self> {
        match std::fs::metadata(path) {
            Ok(meta) if meta.is_dir() => {}
            Ok(meta) => {
                return Err(io::Error::new(
                    io::ErrorKind::InvalidInput,
                    format!(
                        "is {}, not a folder: give a folder for the outputs (it is created if missing)",
                        if meta.is_file() {
                            "a file"
                        } else {
                            kind_of(&meta)
                        }
                    ),
                ));
            }
            Err(e) if e.kind() == io::ErrorKind::NotFound => std::fs::create_dir_all(path)?,
            Err(e) => return Err(e),
        }
        Ok(Self {
            root: path.to_path_buf(),
        })
    }

    /// The folder.
    pub fn path(&self) -> &Path {
        &self.root
    }

    /// The path of the output `name` (a plain file name, no separators).
    pub fn join(&self, name: &str) -> PathBuf {
        debug_assert!(!name.contains(['/', '\\']) && name != ".." && name != ".");
        self.root.join(name)
    }

    /// Write the output `name` whole or not at all ([`write_whole`]).
    pub fn write_whole(&self, name: &str, bytes: &[u8]) -> io::Result<PathBuf> {
        let path = self.join(name);
        write_whole(&path, bytes)?;
        Ok(path)
    }

    /// Start the output `name` afresh ([`create_fresh`]).
    pub fn create_fresh(&self, name: &str) -> io::Result<(PathBuf, File)> {
        let path = self.join(name);
        let file = create_fresh(&path)?;
        Ok((path, file))
    }
}

/// Write `bytes` to `path` whole or not at all: into a sibling temporary
/// file first (created new, so never through a link), renamed over `path`
/// only once complete, so that a full disk or an interrupted run never
/// leaves a truncated file that looks finished. `path` may be missing or a
/// regular file; anything else there (a link, a device, a FIFO, a folder)
/// is refused and left as it is.
pub fn write_whole(path: &Path, bytes: &[u8]) -> io::Result<()> {
    check_target(path)?;
    let partial = partial_path(path);
    let written = File::options()
        .write(true)
        .create_new(true)
        .open(&partial)
        .and_then(|mut f| f.write_all(bytes).and_then(|()| f.flush()))
        .and_then(|()| std::fs::rename(&partial, path));
    written.inspect_err(|_| {
        let _ = std::fs::remove_file(&partial);
    })
}

/// A new, empty regular file at `path`, for an output written as it is
/// computed (a run's CSV: an interrupted run keeps what it computed, and
/// its summary says so). A regular file already there is removed first;
/// anything else is refused. The file is created new (`O_EXCL`), so a link
/// put in its place meanwhile makes this fail rather than be followed.
pub fn create_fresh(path: &Path) -> io::Result<File> {
    if check_target(path)? {
        std::fs::remove_file(path)?;
    }
    File::options().write(true).create_new(true).open(path)
}

/// Whether `a` and `b` name the same existing file (through links and
/// different spellings of the path).
pub fn same_file(a: &Path, b: &Path) -> bool {
    #[cfg(unix)]
    {
        use std::os::unix::fs::MetadataExt;
        match (std::fs::metadata(a), std::fs::metadata(b)) {
            (Ok(x), Ok(y)) => x.dev() == y.dev() && x.ino() == y.ino(),
            _ => false,
        }
    }
    #[cfg(not(unix))]
    {
        match (a.canonicalize(), b.canonicalize()) {
            (Ok(x), Ok(y)) => x == y,
            _ => false,
        }
    }
}

/// Whether `path` holds a regular file (`false`: nothing there); an error
/// for anything else, which an output must not replace or write through.
fn check_target(path: &Path) -> io::Result<bool> {
    match std::fs::symlink_metadata(path) {
        Ok(meta) if meta.is_file() => Ok(true),
        Ok(meta) => Err(io::Error::new(
            io::ErrorKind::InvalidInput,
            format!(
                "is {}: rover writes only regular files, never through a link or over a \
                 device, a FIFO or a folder; remove it or choose another output path",
                kind_of(&meta)
            ),
        )),
        Err(e) if e.kind() == io::ErrorKind::NotFound => Ok(false),
        Err(e) => Err(e),
    }
}

/// The sibling temporary file of `path`: hidden, and named after the
/// process so that two runs writing the same output do not collide.
fn partial_path(path: &Path) -> PathBuf {
    let name = path
        .file_name()
        .map_or_else(|| "output".into(), |n| n.to_string_lossy().into_owned());
    path.with_file_name(format!(".{name}.partial-{}", std::process::id()))
}
