//! The channels a run speaks to Foxglove, in the MCAP log and live alike:
//! their topics, schemas and encodings, and the messages of each row.
//!
//! | topic | schema | when |
//! |---|---|---|
//! | `/tf` | `foxglove.FrameTransforms` (protobuf) | every row |
//! | `/row` | `rover.Row` (JSON, a JSON Schema) | every row: each column of run.csv by name |
//! | `/rover` | `foxglove.SceneUpdate` (protobuf) | once: the rover's parts in their frames |
//! | `/terrain` | `foxglove.SceneUpdate` (protobuf) | once: the ground as a mesh |
//!
//! The protobuf schemas and encoders are the Foxglove SDK's; `/row` is
//! JSON by serde_json, so that the Plot panel reads any column as
//! `/row.<name>` (`/row.Fn1`, `/row.slip2`, `/row.tau3`, `/row.V_set`).

use std::borrow::Cow;

use foxglove::Encode;
use foxglove::messages::{FrameTransforms, SceneUpdate};
use rover_spec::Spec;
use serde::ser::{SerializeMap, Serializer};

use super::frames::{MissingColumn, RoverFrames};
use super::scene::{rover_scene, terrain_scene};
use crate::output::HeightGrid;

/// The frames' topic.
pub const TF: &str = "/tf";
/// The row's topic.
pub const ROW: &str = "/row";
/// The rover's geometry's topic.
pub const ROVER: &str = "/rover";
/// The terrain's topic.
pub const TERRAIN: &str = "/terrain";

/// The row's schema name.
pub const ROW_SCHEMA: &str = "rover.Row";

/// Which channel.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Topic {
    /// `/tf`.
    Tf,
    /// `/row`.
    Row,
    /// `/rover`.
    Rover,
    /// `/terrain`.
    Terrain,
}

impl Topic {
    /// Every channel, in the order they are advertised.
    pub const ALL: [Topic; 4] = [Topic::Tf, Topic::Row, Topic::Rover, Topic::Terrain];

    /// Its topic name.
    pub fn name(self) -> &'static str {
        match self {
            Topic::Tf => TF,
            Topic::Row => ROW,
            Topic::Rover => ROVER,
            Topic::Terrain => TERRAIN,
        }
    }
}

/// A channel's description: what a reader needs to decode it.
#[derive(Clone, Debug)]
pub struct ChannelInfo {
    /// Which.
    pub topic: Topic,
    /// The messages' encoding (`protobuf`, `json`).
    pub message_encoding: String,
    /// The schema's name.
    pub schema_name: String,
    /// The schema's encoding (`protobuf`: a FileDescriptorSet;
    /// `jsonschema`).
    pub schema_encoding: String,
    /// The schema.
    pub schema: Cow<'static, [u8]>,
}

fn info_of<T: Encode>(topic: Topic) -> ChannelInfo {
    // The SDK's own messages all carry their schema.
    let schema = T::get_schema().unwrap_or_else(|| foxglove::Schema::new("", "", Vec::new()));
    ChannelInfo {
        topic,
        message_encoding: T::get_message_encoding(),
        schema_name: schema.name,
        schema_encoding: schema.encoding,
        schema: schema.data,
    }
}

/// A message that could not be encoded.
fn encoding_error(e: impl std::fmt::Display) -> std::io::Error {
    std::io::Error::other(format!("cannot encode a Foxglove message: {e}"))
}

/// The row's JSON Schema: an object of numbers, one per column, each
/// described by its unit.
fn row_schema(names: &[String], units: &[&str]) -> Vec<u8> {
    let properties: serde_json::Map<String, serde_json::Value> = names
        .iter()
        .zip(units.iter().map(Some).chain(std::iter::repeat(None)))
        .map(|(n, u)| {
            let mut p = serde_json::json!({ "type": ["number", "null"] });
            if let Some(u) = u {
                p["description"] = serde_json::Value::from(format!("[{u}]"));
            }
            (n.clone(), p)
        })
        .collect();
    serde_json::json!({
        "title": ROW_SCHEMA,
        "description": "One output row of a rover run: the columns of run.csv (docs/CLI.md)",
        "type": "object",
        "properties": properties,
    })
    .to_string()
    .into_bytes()
}

/// The row as a JSON object, columns in order; a value that is not finite
/// (never in a run's rows, which the CSV writer checks) is `null`.
struct RowJson<'a> {
    names: &'a [String],
    values: &'a [f64],
}

impl serde::Serialize for RowJson<'_> {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        let mut map = s.serialize_map(Some(self.names.len()))?;
        for (n, v) in self.names.iter().zip(self.values) {
            map.serialize_entry(n, &v.is_finite().then_some(*v))?;
        }
        map.end()
    }
}

/// One rover's channels: their descriptions, and each row's messages
/// encoded into buffers reused from row to row.
#[derive(Clone, Debug)]
pub struct Channels {
    names: Vec<String>,
    frames: RoverFrames,
    infos: Vec<ChannelInfo>,
    rover: Vec<u8>,
    tf: Vec<u8>,
    row: Vec<u8>,
}

impl Channels {
    /// The channels of `spec`'s rover for rows of the columns `names`
    /// (`units`: each column's unit, for the row's schema).
    pub fn new(spec: &Spec, names: &[String], units: &[&str]) -> Result<Self, MissingColumn> {
        let frames = RoverFrames::new(spec, names)?;
        let mut rover = Vec::new();
        // Into a Vec: encoding only fails for want of room.
        let _ = rover_scene(spec, &frames).encode(&mut rover);
        let row = ChannelInfo {
            topic: Topic::Row,
            message_encoding: "json".into(),
            schema_name: ROW_SCHEMA.into(),
            schema_encoding: "jsonschema".into(),
            schema: Cow::Owned(row_schema(names, units)),
        };
        Ok(Channels {
            names: names.to_vec(),
            infos: vec![
                info_of::<FrameTransforms>(Topic::Tf),
                row,
                info_of::<SceneUpdate>(Topic::Rover),
                info_of::<SceneUpdate>(Topic::Terrain),
            ],
            frames,
            rover,
            tf: Vec::new(),
            row: Vec::new(),
        })
    }

    /// The channels, in [`Topic::ALL`]'s order.
    pub fn infos(&self) -> &[ChannelInfo] {
        &self.infos
    }

    /// The column names of the rows.
    pub fn names(&self) -> &[String] {
        &self.names
    }

    /// The rover's frames.
    pub fn frames(&self) -> &RoverFrames {
        &self.frames
    }

    /// `/rover`'s one message: the rover's geometry.
    pub fn rover(&self) -> &[u8] {
        &self.rover
    }

    /// `/terrain`'s one message: the ground of `grid` as a mesh.
    pub fn terrain(grid: &HeightGrid) -> std::io::Result<Vec<u8>> {
        let mut out = Vec::new();
        terrain_scene(grid)
            .encode(&mut out)
            .map_err(encoding_error)?;
        Ok(out)
    }

    /// The `/tf` and `/row` messages of the row `values` at time `t`.
    pub fn encode_row(&mut self, t: f64, values: &[f64]) -> std::io::Result<(&[u8], &[u8])> {
        self.tf.clear();
        self.frames
            .update(t, values)
            .encode(&mut self.tf)
            .map_err(encoding_error)?;
        self.row.clear();
        serde_json::to_writer(
            &mut self.row,
            &RowJson {
                names: &self.names,
                values,
            },
        )
        .map_err(encoding_error)?;
        Ok((&self.tf, &self.row))
    }
}
