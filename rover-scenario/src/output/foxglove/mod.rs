//! A run in the robotics tools' formats: the rover's frames, geometry,
//! terrain and rows as Foxglove messages (the SDK's schemas), written to
//! an MCAP log (`run.mcap`) or served live by `rover drive`
//! (docs/VIEW.md).

mod channels;
mod frames;
mod mcap_log;
mod scene;

pub use channels::{ChannelInfo, Channels, ROVER, ROW, ROW_SCHEMA, TERRAIN, TF, Topic};
pub use frames::{
    BODY, Member, MissingColumn, RoverFrames, WORLD, attitude, nanoseconds, timestamp,
};
pub use mcap_log::{MCAP_TERRAIN_NODES, McapLog};
pub use scene::{rover_scene, terrain_scene};
