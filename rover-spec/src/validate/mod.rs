//! Description → [`crate::Spec`]: every check, each with a located message.

mod body;
mod coordinate;
mod names;
mod rover;
pub mod runnable;
mod suspension;
mod wheel;

pub use names::unprintable;
pub use rover::validate;
