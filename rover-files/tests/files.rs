//! Reading refuses what is not a regular file, or too much of one; writing
//! never goes through a link or over anything but a regular file.

#![cfg(unix)]
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

use rover_files::{
    Limit, OutputDir, create_fresh, read, read_entry, read_text, same_file, write_whole,
};

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("rover-files-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn fifo(path: &Path) {
    let status = std::process::Command::new("mkfifo")
        .arg(path)
        .status()
        .unwrap();
    assert!(status.success());
}

fn message(e: std::io::Error) -> String {
    e.to_string()
}

#[test]
fn devices_are_refused_at_once_directly_or_through_a_link() {
    let dir = scratch("devices");
    let link = dir.join("rover.toml");
    std::os::unix::fs::symlink("/dev/zero", &link).unwrap();
    for path in [Path::new("/dev/zero"), Path::new("/dev/urandom"), &link] {
        let e = message(read(path, Limit::Text).unwrap_err());
        assert!(
            e.contains("character device") && e.contains("regular file"),
            "{e}"
        );
    }
    let e = message(read(&dir, Limit::Text).unwrap_err());
    assert!(e.contains("is a directory"), "{e}");
}

#[test]
fn a_fifo_is_refused_without_waiting_for_a_writer() {
    let dir = scratch("fifo");
    let path = dir.join("commands.csv");
    fifo(&path);
    let start = Instant::now();
    let e = message(read_text(&path, Limit::Data).unwrap_err());
    assert!(e.contains("FIFO"), "{e}");
    assert!(start.elapsed() < Duration::from_secs(1));
}

#[test]
fn a_file_beyond_its_cap_is_refused_and_one_within_is_read() {
    let dir = scratch("cap");
    let big = dir.join("big.toml");
    std::fs::File::create(&big)
        .unwrap()
        .set_len(Limit::Text.bytes() + 1)
        .unwrap();
    let e = message(read(&big, Limit::Text).unwrap_err());
    assert!(e.contains("16 MiB"), "{e}");
    // The same file is within a data file's cap.
    assert_eq!(
        read(&big, Limit::Data).unwrap().len() as u64,
        Limit::Text.bytes() + 1
    );
    let small = dir.join("small.toml");
    std::fs::write(&small, "duration = 1.0\n").unwrap();
    let link = dir.join("link.toml");
    std::os::unix::fs::symlink(&small, &link).unwrap();
    assert_eq!(read_text(&link, Limit::Text).unwrap(), "duration = 1.0\n");
}

#[test]
fn text_that_is_not_utf8_is_located() {
    let dir = scratch("utf8");
    let path = dir.join("s.toml");
    std::fs::write(&path, b"a = 1\nb = \"\xff\"\n").unwrap();
    let e = message(read_text(&path, Limit::Text).unwrap_err());
    assert!(e.contains("byte 12 (line 2, column 6)"), "{e}");
}

#[test]
fn a_folder_serves_only_what_it_holds() {
    let dir = scratch("entry");
    let outside = scratch("entry-outside").join("secret.csv");
    std::fs::write(&outside, "secret").unwrap();
    std::os::unix::fs::symlink(&outside, dir.join("run.csv")).unwrap();
    let e = message(read_entry(&dir, "run.csv", Limit::Data).unwrap_err());
    assert!(e.contains("symbolic link"), "{e}");
    std::fs::write(dir.join("summary.json"), "{}").unwrap();
    assert_eq!(
        read_entry(&dir, "summary.json", Limit::Text).unwrap(),
        b"{}"
    );
}

#[test]
fn outputs_never_write_through_a_link_or_over_a_special_file() {
    let dir = scratch("write");
    let target = dir.join("precious.txt");
    std::fs::write(&target, "keep").unwrap();
    let link = dir.join("run.csv");
    std::os::unix::fs::symlink(&target, &link).unwrap();
    let e = message(write_whole(&link, b"new").unwrap_err());
    assert!(e.contains("symbolic link"), "{e}");
    let e = message(create_fresh(&link).unwrap_err());
    assert!(e.contains("symbolic link"), "{e}");
    assert_eq!(std::fs::read_to_string(&target).unwrap(), "keep");
    let pipe = dir.join("summary.json");
    fifo(&pipe);
    let e = message(write_whole(&pipe, b"{}").unwrap_err());
    assert!(e.contains("FIFO"), "{e}");
    let e = message(write_whole(Path::new("/dev/null"), b"x").unwrap_err());
    assert!(e.contains("character device"), "{e}");
    let e = message(write_whole(&dir, b"x").unwrap_err());
    assert!(e.contains("is a directory"), "{e}");
    // Nothing was left behind by the refusals.
    let mut names: Vec<_> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().into_string().unwrap())
        .collect();
    names.sort();
    assert_eq!(names, ["precious.txt", "run.csv", "summary.json"]);
}

#[test]
fn outputs_replace_a_regular_file_whole() {
    let dir = scratch("replace");
    let out = OutputDir::create(&dir.join("a/b")).unwrap();
    let path = out.write_whole("summary.json", b"first").unwrap();
    out.write_whole("summary.json", b"second").unwrap();
    assert_eq!(std::fs::read_to_string(&path).unwrap(), "second");
    let (csv, mut file) = out.create_fresh("run.csv").unwrap();
    std::io::Write::write_all(&mut file, b"t\n").unwrap();
    drop(file);
    let (_, file) = out.create_fresh("run.csv").unwrap();
    drop(file);
    assert_eq!(std::fs::read_to_string(&csv).unwrap(), "");
    assert_eq!(std::fs::read_dir(out.path()).unwrap().count(), 2);
}

#[test]
fn an_output_folder_is_never_a_file_or_device() {
    let dir = scratch("outdir");
    let file = dir.join("rover.toml");
    std::fs::write(&file, "name = \"x\"").unwrap();
    let e = message(OutputDir::create(&file).unwrap_err());
    assert!(e.contains("is a file, not a folder"), "{e}");
    let e = message(OutputDir::create(Path::new("/dev/null")).unwrap_err());
    assert!(e.contains("character device"), "{e}");
    assert_eq!(std::fs::read_to_string(&file).unwrap(), "name = \"x\"");
}

#[test]
fn the_same_file_is_recognized_through_links_and_spellings() {
    let dir = scratch("same");
    let a = dir.join("a.toml");
    std::fs::write(&a, "").unwrap();
    let link = dir.join("b.toml");
    std::os::unix::fs::symlink(&a, &link).unwrap();
    assert!(same_file(&a, &link));
    assert!(same_file(&a, &dir.join(".").join("a.toml")));
    assert!(!same_file(&a, &dir.join("missing.toml")));
}

#[test]
fn an_excerpt_is_short_and_harmless() {
    assert_eq!(rover_files::excerpt("1.5x", 24), "1.5x");
    assert_eq!(
        rover_files::excerpt("root:x:0:0:root:/root:/bin/bash", 8),
        "root:x:0…"
    );
    assert_eq!(rover_files::excerpt("\u{1b}[2J", 8), "\\u{1b}[2J");
}
