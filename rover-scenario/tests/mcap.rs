//! A run's MCAP log read back with the mcap crate: every channel with its
//! schema, as many frames and rows as the CSV has rows, one message of
//! the rover's geometry and one of the terrain; the body's transform is
//! the CSV's pose and the row channel the CSV's numbers. A log that
//! cannot be written stops the run with an error naming it.
#![cfg(feature = "mcap")]

use std::io::{Cursor, Seek, SeekFrom, Write};
use std::path::Path;
use std::sync::atomic::AtomicBool;

use foxglove::Decode;
use foxglove::messages::{FrameTransforms, SceneUpdate};
use rover_scenario::output::RowSink;
use rover_scenario::output::foxglove::{McapLog, attitude};
use rover_scenario::prepare::Prepared;

const SCENARIO: &str = "rover = \"swing4\"
duration = 1.0
output_rate = 40.0
[terrain]
kind = \"random\"
z_r = 0.1
[control.speed]
speed = 0.1
";

fn prepared() -> Prepared {
    Prepared::from_text(None, SCENARIO, Path::new("<mcap test>"), Path::new(".")).unwrap()
}

/// The run's CSV (header, rows) and its MCAP log's bytes.
fn run() -> (Vec<String>, Vec<Vec<f64>>, Vec<u8>) {
    let p = prepared();
    let mut log = McapLog::new(Cursor::new(Vec::new()), &p.spec, "run.mcap").unwrap();
    let mut csv = Vec::new();
    let summary = p
        .run_with_outputs(
            false,
            &mut csv,
            None::<std::io::Sink>,
            Some(&mut log as &mut dyn RowSink),
            &AtomicBool::new(false),
            |_| {},
        )
        .unwrap();
    assert!(summary.complete);
    let text = String::from_utf8(csv).unwrap();
    let mut lines = text.lines();
    let names = lines.next().unwrap().split(',').map(String::from).collect();
    let rows = lines
        .map(|l| l.split(',').map(|v| v.parse().unwrap()).collect())
        .collect();
    (names, rows, log.into_inner().unwrap().into_inner())
}

#[test]
fn the_log_has_every_channel_and_a_frame_and_a_row_per_csv_row() {
    let (names, rows, bytes) = run();
    let summary = mcap::Summary::read(&bytes).unwrap().unwrap();
    let mut channels: Vec<(String, String, String)> = summary
        .channels
        .values()
        .map(|c| {
            let schema = c.schema.as_ref().unwrap();
            (
                c.topic.clone(),
                schema.name.clone(),
                c.message_encoding.clone(),
            )
        })
        .collect();
    channels.sort();
    assert_eq!(
        channels,
        [
            ("/rover", "foxglove.SceneUpdate", "protobuf"),
            ("/row", "rover.Row", "json"),
            ("/terrain", "foxglove.SceneUpdate", "protobuf"),
            ("/tf", "foxglove.FrameTransforms", "protobuf"),
        ]
        .map(|(a, b, c)| (a.to_string(), b.to_string(), c.to_string()))
    );
    let counts = &summary.stats.as_ref().unwrap().channel_message_counts;
    let count = |topic: &str| {
        let id = summary
            .channels
            .values()
            .find(|c| c.topic == topic)
            .unwrap()
            .id;
        counts[&id]
    };
    assert_eq!(rows.len(), 41);
    assert_eq!(count("/tf"), rows.len() as u64);
    assert_eq!(count("/row"), rows.len() as u64);
    assert_eq!((count("/rover"), count("/terrain")), (1, 1));

    let col = |n: &str| names.iter().position(|c| c == n).unwrap();
    let (mut tf, mut row) = (0, 0);
    for m in mcap::MessageStream::new(&bytes).unwrap() {
        let m = m.unwrap();
        match m.channel.topic.as_str() {
            "/tf" => {
                let r = &rows[tf];
                assert_eq!(m.log_time, (r[0] * 1e9).round() as u64);
                let frames = FrameTransforms::decode(&m.data[..]).unwrap();
                let body = &frames.transforms[0];
                assert_eq!(
                    (body.parent_frame_id.as_str(), body.child_frame_id.as_str()),
                    ("world", "body")
                );
                let at = body.translation.unwrap();
                assert_eq!([at.x, at.y, at.z], [r[col("X")], r[col("Y")], r[col("Z")]]);
                let q = body.rotation.unwrap();
                let expected = attitude(r[col("phi")], r[col("theta")], r[col("psi")]);
                let dot = q.w * expected.w + q.x * expected.i + q.y * expected.j + q.z * expected.k;
                assert!((dot.abs() - 1.0).abs() < 1e-12, "{q:?} {expected:?}");
                // Body, four swing arms, four wheels.
                assert_eq!(frames.transforms.len(), 9);
                tf += 1;
            }
            "/row" => {
                // Valid JSON, its numbers read exactly (std's parser:
                // serde_json's default one is not exact to the last bit).
                let text = std::str::from_utf8(&m.data).unwrap();
                let v: serde_json::Value = serde_json::from_str(text).unwrap();
                assert_eq!(v.as_object().unwrap().len(), names.len());
                let pairs: Vec<(String, f64)> = text
                    .trim_matches(['{', '}'])
                    .split(',')
                    .map(|p| {
                        let (k, x) = p.split_once(':').unwrap();
                        (k.trim_matches('"').to_string(), x.parse().unwrap())
                    })
                    .collect();
                let expected: Vec<(String, f64)> = names
                    .iter()
                    .cloned()
                    .zip(rows[row].iter().copied())
                    .collect();
                assert_eq!(pairs, expected);
                row += 1;
            }
            _ => {
                let scene = SceneUpdate::decode(&m.data[..]).unwrap();
                assert!(!scene.entities.is_empty());
            }
        }
    }
    assert_eq!((tf, row), (rows.len(), rows.len()));
}

/// A sink that takes `left` bytes, then fails as a full disk does.
struct Full {
    inner: Cursor<Vec<u8>>,
    left: usize,
}

impl Write for Full {
    fn write(&mut self, buf: &[u8]) -> std::io::Result<usize> {
        if buf.len() > self.left {
            return Err(std::io::Error::other("no space left on device"));
        }
        self.left -= buf.len();
        self.inner.write(buf)
    }
    fn flush(&mut self) -> std::io::Result<()> {
        Ok(())
    }
}

impl Seek for Full {
    fn seek(&mut self, pos: SeekFrom) -> std::io::Result<u64> {
        self.inner.seek(pos)
    }
}

#[test]
fn a_log_that_cannot_be_written_stops_the_run_naming_it() {
    let p = prepared();
    let full = Full {
        inner: Cursor::new(Vec::new()),
        left: 2000,
    };
    let mut log = McapLog::new(full, &p.spec, "out/run.mcap").unwrap();
    let e = p
        .run_with_outputs(
            false,
            std::io::sink(),
            None::<std::io::Sink>,
            Some(&mut log as &mut dyn RowSink),
            &AtomicBool::new(false),
            |_| {},
        )
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("out/run.mcap: ") && e.contains("no space left on device"),
        "{e}"
    );
}
