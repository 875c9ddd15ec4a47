//! `run.mcap`: the run's rows as an MCAP log of Foxglove messages
//! ([`super::channels`]), written by the `mcap` crate as the run goes,
//! each message stamped with simulated time (t = 0 is the epoch).
//!
//! The file is chunked and indexed, uncompressed (the compressions are C
//! libraries; see the workspace's Cargo.toml). `/rover` is written at
//! the first row, `/terrain` at the end (stamped t = 0: a reader orders
//! messages by time through the index) over the ground the path covered,
//! [`crate::output::PATH_MARGIN`] wider on every side.

use std::collections::BTreeMap;
use std::io::{Seek, Write};

use rover_runtime::row::Columns;
use rover_spec::Spec;
use rover_terrain::Terrain;

use super::channels::{Channels, Topic};
use crate::output::{PathBox, RowSink};

/// Most terrain nodes along the mesh's longer side: 192 × 192 nodes, a
/// few MB.
pub const MCAP_TERRAIN_NODES: usize = 192;

/// An MCAP log of a run, a [`RowSink`].
pub struct McapLog<W: Write + Seek> {
    label: String,
    spec: Spec,
    writer: Option<mcap::Writer<W>>,
    /// The sink, once the log is finished.
    done: Option<W>,
    channels: Option<Channels>,
    ids: [u16; 4],
    sequence: u32,
    path: PathBox,
    rows: u64,
}

impl<W: Write + Seek> std::fmt::Debug for McapLog<W> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("McapLog")
            .field("label", &self.label)
            .field("rows", &self.rows)
            .finish()
    }
}

impl<W: Write + Seek> McapLog<W> {
    /// A log of `spec`'s rover into `out`; `label` (its file's name) heads
    /// its errors. Writes the file's header.
    pub fn new(out: W, spec: &Spec, label: impl Into<String>) -> std::io::Result<Self> {
        let label = label.into();
        let options = mcap::WriteOptions::new()
            .compression(None)
            .profile("")
            .library(format!("rover {}", env!("CARGO_PKG_VERSION")));
        let writer = match options.create(out) {
            Ok(w) => w,
            Err(mcap::McapError::Io(e)) => {
                return Err(std::io::Error::new(e.kind(), format!("{label}: {e}")));
            }
            Err(e) => return Err(std::io::Error::other(format!("{label}: {e}"))),
        };
        Ok(McapLog {
            label,
            spec: spec.clone(),
            writer: Some(writer),
            done: None,
            channels: None,
            ids: [0; 4],
            sequence: 0,
            path: PathBox::default(),
            rows: 0,
        })
    }

    /// Rows written so far.
    pub fn rows(&self) -> u64 {
        self.rows
    }

    /// The sink the log was written to, once finished
    /// ([`RowSink::finish`]).
    pub fn into_inner(self) -> Option<W> {
        self.done
    }

    /// An error of the log, headed by its name, with its causes (the
    /// mcap crate's I/O error says only that it was one).
    fn failed(&self, e: impl std::error::Error) -> std::io::Error {
        let mut text = format!("{}: {e}", self.label);
        let mut cause = e.source();
        while let Some(c) = cause {
            text.push_str(&format!(": {c}"));
            cause = c.source();
        }
        std::io::Error::other(text)
    }

    fn write(&mut self, topic: Topic, t_ns: u64, data: &[u8]) -> std::io::Result<()> {
        let header = mcap::records::MessageHeader {
            channel_id: self.ids[topic as usize],
            sequence: self.sequence,
            log_time: t_ns,
            publish_time: t_ns,
        };
        self.sequence = self.sequence.wrapping_add(1);
        let Some(w) = self.writer.as_mut() else {
            return Err(std::io::Error::other("the log is finished"));
        };
        let r = w.write_to_known_channel(&header, data);
        r.map_err(|e| self.failed(e))
    }
}

impl<W: Write + Seek> RowSink for McapLog<W> {
    fn start(&mut self, columns: &Columns) -> std::io::Result<()> {
        let units = columns.units(&self.spec.coordinate_linear);
        let channels =
            Channels::new(&self.spec, columns.names(), &units).map_err(|e| self.failed(e))?;
        let Some(w) = self.writer.as_mut() else {
            return Err(std::io::Error::other("the log is finished"));
        };
        let mut ids = [0u16; 4];
        let mut fail = None;
        for info in channels.infos() {
            let r = w
                .add_schema(&info.schema_name, &info.schema_encoding, &info.schema)
                .and_then(|schema| {
                    w.add_channel(
                        schema,
                        info.topic.name(),
                        &info.message_encoding,
                        &BTreeMap::new(),
                    )
                });
            match r {
                Ok(id) => ids[info.topic as usize] = id,
                Err(e) => {
                    fail = Some(e);
                    break;
                }
            }
        }
        if let Some(e) = fail {
            return Err(self.failed(e));
        }
        self.ids = ids;
        self.path.start(columns);
        self.channels = Some(channels);
        Ok(())
    }

    fn row(&mut self, values: &[f64]) -> std::io::Result<()> {
        let Some(mut channels) = self.channels.take() else {
            return Err(std::io::Error::other("a row before the columns"));
        };
        let t = values[0];
        let ns = super::frames::nanoseconds(t);
        let result = (|| {
            if self.rows == 0 {
                self.write(Topic::Rover, ns, channels.rover())?;
            }
            let (tf, row) = channels.encode_row(t, values)?;
            self.write(Topic::Tf, ns, tf)?;
            self.write(Topic::Row, ns, row)
        })();
        self.channels = Some(channels);
        result?;
        self.rows += 1;
        self.path.add(values);
        Ok(())
    }

    fn finish(&mut self, terrain: Option<&Terrain>) -> std::io::Result<()> {
        if let Some(grid) = terrain.and_then(|t| self.path.ground(t, MCAP_TERRAIN_NODES)) {
            let mesh = Channels::terrain(&grid)?;
            self.write(Topic::Terrain, 0, &mesh)?;
        }
        let Some(mut w) = self.writer.take() else {
            return Ok(());
        };
        w.finish().map_err(|e| self.failed(e))?;
        let mut out = w.into_inner();
        out.flush().map_err(|e| self.failed(e))?;
        self.done = Some(out);
        Ok(())
    }
}
