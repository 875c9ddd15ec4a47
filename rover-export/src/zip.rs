//! A zip archive of stored (uncompressed) entries, as an FMU is: the
//! format's local headers, central directory and end record (PKWARE's
//! APPNOTE 6.3, sections 4.3 and 4.4), without compression or ZIP64. An
//! FMU of a built-in rover is a few MB, mostly its library; stored entries
//! keep the writer a page long with no compression crate, and every
//! importer reads them.

use std::io::{self, Write};

/// One entry to store: its path inside the archive (`/`-separated) and
/// its bytes.
#[derive(Clone, Debug)]
pub struct Entry {
    /// Path inside the archive.
    pub name: String,
    /// The file's bytes.
    pub data: Vec<u8>,
}

/// Write `entries` as a zip archive to `out`. Entries and the archive must
/// stay under 4 GiB (no ZIP64); larger ones are refused.
pub fn write_zip<W: Write>(out: &mut W, entries: &[Entry]) -> io::Result<()> {
    let too_big = |what: &str| {
        io::Error::new(
            io::ErrorKind::InvalidInput,
            format!("{what} is 4 GiB or more: the FMU's zip has no ZIP64"),
        )
    };
    let mut central = Vec::new();
    let mut offset: u64 = 0;
    // 1980-01-01 00:00, the format's earliest time: archives of the same
    // files are the same bytes.
    let (time, date): (u16, u16) = (0, (1 << 5) | 1);
    for e in entries {
        let crc = crc32fast::hash(&e.data);
        let size = u32::try_from(e.data.len()).map_err(|_| too_big(&e.name))?;
        let name = e.name.as_bytes();
        let name_len = u16::try_from(name.len()).map_err(|_| too_big(&e.name))?;
        let here = u32::try_from(offset).map_err(|_| too_big("the archive"))?;
        let mut local = Vec::with_capacity(30 + name.len());
        local.extend_from_slice(&0x0403_4b50u32.to_le_bytes());
        local.extend_from_slice(&20u16.to_le_bytes()); // version needed: 2.0
        local.extend_from_slice(&0x0800u16.to_le_bytes()); // flags: UTF-8 names
        local.extend_from_slice(&0u16.to_le_bytes()); // method: stored
        local.extend_from_slice(&time.to_le_bytes());
        local.extend_from_slice(&date.to_le_bytes());
        local.extend_from_slice(&crc.to_le_bytes());
        local.extend_from_slice(&size.to_le_bytes()); // compressed size
        local.extend_from_slice(&size.to_le_bytes()); // uncompressed size
        local.extend_from_slice(&name_len.to_le_bytes());
        local.extend_from_slice(&0u16.to_le_bytes()); // extra field length
        local.extend_from_slice(name);
        out.write_all(&local)?;
        out.write_all(&e.data)?;

        central.extend_from_slice(&0x0201_4b50u32.to_le_bytes());
        central.extend_from_slice(&((3u16 << 8) | 20).to_le_bytes()); // made by: Unix, 2.0
        central.extend_from_slice(&20u16.to_le_bytes());
        central.extend_from_slice(&0x0800u16.to_le_bytes());
        central.extend_from_slice(&0u16.to_le_bytes());
        central.extend_from_slice(&time.to_le_bytes());
        central.extend_from_slice(&date.to_le_bytes());
        central.extend_from_slice(&crc.to_le_bytes());
        central.extend_from_slice(&size.to_le_bytes());
        central.extend_from_slice(&size.to_le_bytes());
        central.extend_from_slice(&name_len.to_le_bytes());
        central.extend_from_slice(&0u16.to_le_bytes()); // extra
        central.extend_from_slice(&0u16.to_le_bytes()); // comment
        central.extend_from_slice(&0u16.to_le_bytes()); // disk
        central.extend_from_slice(&0u16.to_le_bytes()); // internal attributes
        // External attributes: a regular file, rw-r--r-- (rwxr-xr-x for a library).
        let mode: u32 = if e.name.ends_with(".so") || e.name.ends_with(".dylib") {
            0o100755
        } else {
            0o100644
        };
        central.extend_from_slice(&(mode << 16).to_le_bytes());
        central.extend_from_slice(&here.to_le_bytes());
        central.extend_from_slice(name);
        offset += local.len() as u64 + e.data.len() as u64;
    }
    let count = u16::try_from(entries.len()).map_err(|_| too_big("the number of entries"))?;
    let cd_offset = u32::try_from(offset).map_err(|_| too_big("the archive"))?;
    let cd_size = u32::try_from(central.len()).map_err(|_| too_big("the directory"))?;
    out.write_all(&central)?;
    let mut end = Vec::with_capacity(22);
    end.extend_from_slice(&0x0605_4b50u32.to_le_bytes());
    end.extend_from_slice(&0u16.to_le_bytes());
    end.extend_from_slice(&0u16.to_le_bytes());
    end.extend_from_slice(&count.to_le_bytes());
    end.extend_from_slice(&count.to_le_bytes());
    end.extend_from_slice(&cd_size.to_le_bytes());
    end.extend_from_slice(&cd_offset.to_le_bytes());
    end.extend_from_slice(&0u16.to_le_bytes()); // comment length
    out.write_all(&end)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The archive read back by hand: each local header's name, sizes and
    /// checksum, the data after it, and the end record's count and offset.
    #[test]
    fn entries_read_back_from_their_headers() {
        let entries = vec![
            Entry {
                name: "modelDescription.xml".into(),
                data: b"<fmiModelDescription/>".to_vec(),
            },
            Entry {
                name: "resources/empty".into(),
                data: Vec::new(),
            },
        ];
        let mut zip = Vec::new();
        write_zip(&mut zip, &entries).unwrap();
        let u16_at = |i: usize| u16::from_le_bytes([zip[i], zip[i + 1]]) as usize;
        let u32_at = |i: usize| u32::from_le_bytes(zip[i..i + 4].try_into().unwrap());
        let mut at = 0;
        for e in &entries {
            assert_eq!(u32_at(at), 0x0403_4b50);
            assert_eq!(u32_at(at + 14), crc32fast::hash(&e.data));
            assert_eq!(u32_at(at + 18) as usize, e.data.len());
            let n = u16_at(at + 26);
            assert_eq!(&zip[at + 30..at + 30 + n], e.name.as_bytes());
            let data = at + 30 + n;
            assert_eq!(&zip[data..data + e.data.len()], &e.data[..]);
            at = data + e.data.len();
        }
        let end = zip.len() - 22;
        assert_eq!(u32_at(end), 0x0605_4b50);
        assert_eq!(u16_at(end + 10), 2);
        assert_eq!(
            u32_at(end + 16) as usize,
            at,
            "the directory follows the last entry"
        );
        // The checksum of a known string (the format's CRC-32).
        assert_eq!(crc32fast::hash(b"123456789"), 0xcbf4_3926);
    }
}
