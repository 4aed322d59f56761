//! The zip container of a NumPy `.npz` through the `zip` crate: entries
//! stored (`np.savez`) or deflated (`np.savez_compressed`), ZIP64 sizes and
//! offsets, CRC-32 checked. Encrypted entries and other compression methods
//! are refused by name. An entry is read only up to [`MAX_ENTRY`] bytes
//! (and never past what its header declares), so that a hostile size costs
//! no more memory than that.

use std::io::Read;

/// The most bytes one entry may hold uncompressed (1 GiB).
pub const MAX_ENTRY: u64 = 1 << 30;

/// The names and contents of every entry of the archive `bytes`.
pub(crate) fn entries(bytes: &[u8]) -> Result<Vec<(String, Vec<u8>)>, String> {
    let mut archive = zip::ZipArchive::new(std::io::Cursor::new(bytes))
        .map_err(|e| format!("not a zip file, or cut short ({e})"))?;
    let mut out = Vec::with_capacity(archive.len().min(1024));
    for i in 0..archive.len() {
        let mut entry = archive.by_index(i).map_err(|e| match e {
            zip::result::ZipError::UnsupportedArchive(m) => format!("entry {}: {m}", i + 1),
            e => format!("entry {}: {e}", i + 1),
        })?;
        let name = entry
            .name()
            .map_err(|e| format!("entry {}: its name cannot be read ({e})", i + 1))?
            .to_string();
        let size = entry.size();
        if size > MAX_ENTRY {
            return Err(format!(
                "entry `{name}` claims {size} bytes (more than the {MAX_ENTRY} read)"
            ));
        }
        let mut data = Vec::new();
        (&mut entry)
            .take(size)
            .read_to_end(&mut data)
            .map_err(|e| {
                format!("entry `{name}` is damaged: size or CRC-32 does not match ({e})")
            })?;
        // Reading to the end checks the CRC-32.
        let mut rest = [0u8; 1];
        let more = entry.read(&mut rest).map_err(|e| {
            format!("entry `{name}` is damaged: size or CRC-32 does not match ({e})")
        })?;
        if data.len() as u64 != size || more != 0 {
            return Err(format!(
                "entry `{name}` is damaged: size or CRC-32 does not match"
            ));
        }
        out.push((name, data));
    }
    Ok(out)
}

/// A zip archive of `entries`, deflated when `deflate` (tests: an archive to
/// read back, laid out as Python's `zipfile` writes it).
#[cfg(test)]
pub(crate) fn write(entries: &[(&str, Vec<u8>)], deflate: bool) -> Vec<u8> {
    use std::io::Write;
    let mut out = Vec::new();
    let mut central = Vec::new();
    for (name, data) in entries {
        let mut crc = flate2::Crc::new();
        crc.update(data);
        let body = if deflate {
            let mut enc =
                flate2::write::DeflateEncoder::new(Vec::new(), flate2::Compression::default());
            enc.write_all(data).unwrap();
            enc.finish().unwrap()
        } else {
            data.clone()
        };
        let method: u16 = if deflate { 8 } else { 0 };
        let offset = out.len() as u32;
        let head = |sig: u32, central: bool| {
            let mut h = sig.to_le_bytes().to_vec();
            if central {
                h.extend(20u16.to_le_bytes());
            }
            h.extend(20u16.to_le_bytes());
            h.extend(0u16.to_le_bytes());
            h.extend(method.to_le_bytes());
            h.extend([0u8; 4]);
            h.extend(crc.sum().to_le_bytes());
            h.extend((body.len() as u32).to_le_bytes());
            h.extend((data.len() as u32).to_le_bytes());
            h.extend((name.len() as u16).to_le_bytes());
            h.extend(0u16.to_le_bytes());
            if central {
                h.extend([0u8; 10]);
                h.extend(offset.to_le_bytes());
            }
            h.extend(name.bytes());
            h
        };
        out.extend(head(0x0403_4b50, false));
        out.extend(&body);
        central.extend(head(0x0201_4b50, true));
    }
    let dir = out.len() as u32;
    out.extend(&central);
    out.extend(0x0605_4b50u32.to_le_bytes());
    out.extend([0u8; 4]);
    out.extend((entries.len() as u16).to_le_bytes());
    out.extend((entries.len() as u16).to_le_bytes());
    out.extend((central.len() as u32).to_le_bytes());
    out.extend(dir.to_le_bytes());
    out.extend(0u16.to_le_bytes());
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn stored_and_deflated_entries_read_back() {
        let a = b"first entry".to_vec();
        let b: Vec<u8> = (0..5000u32).map(|k| (k % 7) as u8).collect();
        for deflate in [false, true] {
            let zip = write(&[("a.npy", a.clone()), ("b.npy", b.clone())], deflate);
            let got = entries(&zip).unwrap();
            assert_eq!(
                got,
                vec![
                    ("a.npy".to_string(), a.clone()),
                    ("b.npy".to_string(), b.clone())
                ]
            );
        }
    }

    #[test]
    fn damage_is_named() {
        assert!(entries(b"not a zip at all, just some text")
            .unwrap_err()
            .contains("not a zip file"));
        let mut zip = write(&[("a.npy", b"hello".to_vec())], false);
        let at = zip.iter().position(|&c| c == b'h').unwrap();
        zip[at] = b'j';
        assert!(entries(&zip)
            .unwrap_err()
            .starts_with("entry `a.npy` is damaged: size or CRC-32 does not match"));
        let zip = write(&[("a.npy", b"hello".to_vec())], false);
        assert!(entries(&zip[..zip.len() - 30]).is_err());
    }
}
