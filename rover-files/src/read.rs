//! Reading: regular files only, capped by the kind of file expected.

use std::fs::{File, Metadata};
use std::io::{self, Read};
use std::path::Path;

/// The most rover reads from one file, by what the file is meant to be.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Limit {
    /// A text file written by hand: a rover description, a scenario, a
    /// soil, a sweep plan (16 MiB, a hundred times the largest we ship).
    Text,
    /// A data file: a terrain raster or CSV, a command log, a run's CSV,
    /// a sweep record (1 GiB: a 16k × 16k terrain of 32-bit floats).
    Data,
}

impl Limit {
    /// The cap in bytes.
    pub fn bytes(self) -> u64 {
        match self {
            Limit::Text => 16 << 20,
            Limit::Data => 1 << 30,
        }
    }

    fn describe(self) -> &'static str {
        match self {
            Limit::Text => {
                "16 MiB, the most rover reads from a text file (a rover, a scenario, a soil, a plan)"
            }
            Limit::Data => {
                "1 GiB, the most rover reads from a data file (a terrain, a command log, a run)"
            }
        }
    }
}

/// The bytes of the regular file at `path` (links followed), at most
/// `limit`'s cap.
pub fn read(path: &Path, limit: Limit) -> io::Result<Vec<u8>> {
    let file = open_regular(path)?;
    let cap = limit.bytes();
    let expected = file.metadata().map_or(0, |m| m.len());
    if expected > cap {
        return Err(too_large(limit));
    }
    let mut bytes = Vec::with_capacity(expected as usize);
    // One byte past the cap tells a file that grew while being read.
    file.take(cap + 1).read_to_end(&mut bytes)?;
    if bytes.len() as u64 > cap {
        return Err(too_large(limit));
    }
    Ok(bytes)
}

/// The UTF-8 text of the regular file at `path`, at most `limit`'s cap.
/// Text that is not UTF-8 is an [`io::ErrorKind::InvalidData`] error
/// carrying a [`NotUtf8`] (its place, for callers that report lines).
pub fn read_text(path: &Path, limit: Limit) -> io::Result<String> {
    String::from_utf8(read(path, limit)?).map_err(|e| {
        let byte = e.utf8_error().valid_up_to();
        let (line, column) = line_column(e.as_bytes(), byte);
        io::Error::new(io::ErrorKind::InvalidData, NotUtf8 { byte, line, column })
    })
}

/// Where a file stops being UTF-8 text.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct NotUtf8 {
    /// The first bad byte, from 0.
    pub byte: usize,
    /// Its 1-based line.
    pub line: usize,
    /// Its 1-based column (in characters).
    pub column: usize,
}

impl NotUtf8 {
    /// The place of the first bad byte in `error`, if it is one of these.
    pub fn of(error: &io::Error) -> Option<NotUtf8> {
        error.get_ref()?.downcast_ref::<NotUtf8>().copied()
    }
}

impl std::fmt::Display for NotUtf8 {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "is not UTF-8 text: byte {} (line {}, column {}) is not valid UTF-8; \
             save it as UTF-8 text (is it a binary file?)",
            self.byte + 1,
            self.line,
            self.column
        )
    }
}

impl std::error::Error for NotUtf8 {}

/// The bytes of the file `name` directly inside `dir`, which must be a
/// regular file there and not a link to one elsewhere: what a server of
/// the folder may hand out.
pub fn read_entry(dir: &Path, name: &str, limit: Limit) -> io::Result<Vec<u8>> {
    let path = dir.join(name);
    let meta = std::fs::symlink_metadata(&path)?;
    if meta.file_type().is_symlink() {
        return Err(io::Error::new(
            io::ErrorKind::InvalidInput,
            "is a symbolic link: only files that the folder itself holds are read from it",
        ));
    }
    read(&path, limit)
}

/// 1-based line and column (in characters) of byte `at` of `bytes`.
pub fn line_column(bytes: &[u8], at: usize) -> (usize, usize) {
    let before = &bytes[..at.min(bytes.len())];
    let line = before.iter().filter(|&&b| b == b'\n').count() + 1;
    let start = before
        .iter()
        .rposition(|&b| b == b'\n')
        .map_or(0, |p| p + 1);
    let column = String::from_utf8_lossy(&before[start..]).chars().count() + 1;
    (line, column)
}

fn too_large(limit: Limit) -> io::Error {
    io::Error::new(
        io::ErrorKind::InvalidInput,
        format!("is larger than {}: is it the right file?", limit.describe()),
    )
}

/// Open `path` for reading if it is a regular file. The check is made on
/// the opened handle (so that a file swapped after a check cannot slip
/// through), and the open does not wait for a FIFO's writer.
fn open_regular(path: &Path) -> io::Result<File> {
    let mut options = std::fs::OpenOptions::new();
    options.read(true);
    #[cfg(unix)]
    {
        use std::os::unix::fs::OpenOptionsExt;
        options.custom_flags(libc::O_NONBLOCK);
    }
    let file = options.open(path)?;
    let meta = file.metadata()?;
    if !meta.is_file() {
        return Err(not_regular(&meta));
    }
    #[cfg(unix)]
    clear_nonblocking(&file)?;
    Ok(file)
}

/// Reads of a regular file never block; the flag is cleared all the same so
/// that the handle behaves as any other.
#[cfg(unix)]
fn clear_nonblocking(file: &File) -> io::Result<()> {
    use std::os::fd::AsRawFd;
    let fd = file.as_raw_fd();
    // SAFETY: `fd` is an open descriptor owned by `file` for this call.
    let flags = unsafe { libc::fcntl(fd, libc::F_GETFL) };
    if flags < 0 {
        return Err(io::Error::last_os_error());
    }
    // SAFETY: as above; only O_NONBLOCK changes.
    if unsafe { libc::fcntl(fd, libc::F_SETFL, flags & !libc::O_NONBLOCK) } < 0 {
        return Err(io::Error::last_os_error());
    }
    Ok(())
}

/// The error for a path that is not a regular file, naming what it is.
pub(crate) fn not_regular(meta: &Metadata) -> io::Error {
    io::Error::new(
        io::ErrorKind::InvalidInput,
        format!(
            "is {}, not a regular file: give the path of a file",
            kind_of(meta)
        ),
    )
}

/// What a non-regular file is, in words.
pub(crate) fn kind_of(meta: &Metadata) -> &'static str {
    let t = meta.file_type();
    if t.is_dir() {
        return "a directory";
    }
    if t.is_symlink() {
        return "a symbolic link";
    }
    #[cfg(unix)]
    {
        use std::os::unix::fs::FileTypeExt;
        if t.is_char_device() {
            return "a character device";
        }
        if t.is_block_device() {
            return "a block device";
        }
        if t.is_fifo() {
            return "a FIFO (named pipe)";
        }
        if t.is_socket() {
            return "a socket";
        }
    }
    "a special file"
}

/// At most `max` characters of `text` (a token of a file being reported),
/// control characters escaped: enough to find it in one's own file, never a
/// whole line of someone else's, nor an escape sequence for the terminal.
pub fn excerpt(text: &str, max: usize) -> String {
    let mut out = String::new();
    for c in text.chars().take(max) {
        if c.is_control() {
            out.extend(c.escape_default());
        } else {
            out.push(c);
        }
    }
    if text.chars().nth(max).is_some() {
        out.push('…');
    }
    out
}
