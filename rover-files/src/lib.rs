//! The one way rover reads the files a user names and writes its outputs.
//!
//! Every file that a command line, a scenario or a sweep names is read by
//! [`read`] or [`read_text`]: only a regular file (a symbolic link to one
//! is fine), never a device, a FIFO, a socket or a folder, and never more
//! than a cap that says what kind of file it was meant to be. `/dev/zero`
//! given as a rover is refused at once instead of filling memory, and a
//! FIFO is refused instead of blocking forever (it is opened without
//! waiting for a writer).
//!
//! Every output is written by [`write_whole`], [`create_fresh`] or through
//! an [`OutputDir`]: regular files only, never through a symbolic link,
//! never over a device, a FIFO or a folder, and a file that is meant to be
//! whole is renamed into place only once complete.
//!
//! Errors are [`std::io::Error`]s whose text says what is wrong and how to
//! fix it, so that every caller's error type (which names the file) can
//! carry them unchanged.

mod number;
mod read;
mod write;

pub use number::{push_f64, write_f64};
pub use read::{Limit, NotUtf8, excerpt, line_column, read, read_entry, read_text};
pub use write::{OutputDir, create_fresh, same_file, write_whole};
