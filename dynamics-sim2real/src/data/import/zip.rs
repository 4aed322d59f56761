//! The zip container of a NumPy `.npz`: the central directory read from the
//! end of the file, entries stored (`np.savez`) or deflated
//! (`np.savez_compressed`, through `flate2`, already a dependency for
//! `.csv.gz`), ZIP64 sizes and offsets, CRC-32 checked. Encrypted entries,
//! split archives and other compression methods are refused by name.

use std::io::Read;

/// One entry's name and where its data lie.
struct Entry {
    name: String,
    method: u16,
    crc: u32,
    compressed: u64,
    size: u64,
    offset: u64,
    flags: u16,
}

fn u16_at(b: &[u8], at: usize) -> Option<u16> {
    Some(u16::from_le_bytes(b.get(at..at + 2)?.try_into().ok()?))
}
fn u32_at(b: &[u8], at: usize) -> Option<u32> {
    Some(u32::from_le_bytes(b.get(at..at + 4)?.try_into().ok()?))
}
fn u64_at(b: &[u8], at: usize) -> Option<u64> {
    Some(u64::from_le_bytes(b.get(at..at + 8)?.try_into().ok()?))
}

/// The names and contents of every entry of the archive `bytes`.
pub(crate) fn entries(bytes: &[u8]) -> Result<Vec<(String, Vec<u8>)>, String> {
    let cut = || "the archive is cut short".to_string();
    // End of central directory: 22 bytes plus a comment of up to 65535.
    let lowest = bytes.len().saturating_sub(22 + 65535);
    let eocd = (lowest..bytes.len().saturating_sub(21))
        .rev()
        .find(|&i| u32_at(bytes, i) == Some(0x0605_4b50))
        .ok_or("no end-of-central-directory record (not a zip file)")?;
    let mut count = u16_at(bytes, eocd + 10).ok_or_else(cut)? as u64;
    let mut dir = u32_at(bytes, eocd + 16).ok_or_else(cut)? as u64;
    if u16_at(bytes, eocd + 4) != Some(0) {
        return Err("a split (multi-disk) archive".into());
    }
    // ZIP64 end of central directory, found through its locator.
    if (count == 0xFFFF || dir == 0xFFFF_FFFF)
        && eocd >= 20
        && u32_at(bytes, eocd - 20) == Some(0x0706_4b50)
    {
        let at = u64_at(bytes, eocd - 12).ok_or_else(cut)? as usize;
        if u32_at(bytes, at) != Some(0x0606_4b50) {
            return Err("the ZIP64 end record is not where its locator says".into());
        }
        count = u64_at(bytes, at + 32).ok_or_else(cut)?;
        dir = u64_at(bytes, at + 48).ok_or_else(cut)?;
    }
    let mut at = dir as usize;
    let mut list = Vec::new();
    for _ in 0..count {
        if u32_at(bytes, at) != Some(0x0201_4b50) {
            return Err(format!("no central directory entry at byte {at}"));
        }
        let name_len = u16_at(bytes, at + 28).ok_or_else(cut)? as usize;
        let extra_len = u16_at(bytes, at + 30).ok_or_else(cut)? as usize;
        let comment_len = u16_at(bytes, at + 32).ok_or_else(cut)? as usize;
        let name = bytes.get(at + 46..at + 46 + name_len).ok_or_else(cut)?;
        let mut e = Entry {
            name: String::from_utf8_lossy(name).into_owned(),
            flags: u16_at(bytes, at + 8).ok_or_else(cut)?,
            method: u16_at(bytes, at + 10).ok_or_else(cut)?,
            crc: u32_at(bytes, at + 16).ok_or_else(cut)?,
            compressed: u32_at(bytes, at + 20).ok_or_else(cut)? as u64,
            size: u32_at(bytes, at + 24).ok_or_else(cut)? as u64,
            offset: u32_at(bytes, at + 42).ok_or_else(cut)? as u64,
        };
        let extra = bytes
            .get(at + 46 + name_len..at + 46 + name_len + extra_len)
            .ok_or_else(cut)?;
        zip64_extra(extra, &mut e);
        list.push(e);
        at += 46 + name_len + extra_len + comment_len;
    }
    list.into_iter().map(|e| read_entry(bytes, e)).collect()
}

/// Replaces the 0xFFFFFFFF fields of `e` by the ZIP64 extra field's values.
fn zip64_extra(extra: &[u8], e: &mut Entry) {
    let mut k = 0;
    while k + 4 <= extra.len() {
        let (id, len) = (
            u16_at(extra, k).unwrap_or(0),
            u16_at(extra, k + 2).unwrap_or(0) as usize,
        );
        if id == 1 {
            let mut p = k + 4;
            for field in [&mut e.size, &mut e.compressed, &mut e.offset] {
                if *field == 0xFFFF_FFFF {
                    if let Some(v) = u64_at(extra, p) {
                        *field = v;
                    }
                    p += 8;
                }
            }
        }
        k += 4 + len;
    }
}

/// The data of one entry, inflated and checked.
fn read_entry(bytes: &[u8], e: Entry) -> Result<(String, Vec<u8>), String> {
    let cut = || format!("entry `{}` is cut short", e.name);
    if e.flags & 1 != 0 {
        return Err(format!("entry `{}` is encrypted", e.name));
    }
    let at = e.offset as usize;
    if u32_at(bytes, at) != Some(0x0403_4b50) {
        return Err(format!("entry `{}`: no local header at byte {at}", e.name));
    }
    let name_len = u16_at(bytes, at + 26).ok_or_else(cut)? as usize;
    let extra_len = u16_at(bytes, at + 28).ok_or_else(cut)? as usize;
    let start = at + 30 + name_len + extra_len;
    let raw = bytes
        .get(start..start + e.compressed as usize)
        .ok_or_else(cut)?;
    let data = match e.method {
        0 => raw.to_vec(),
        8 => {
            let mut out = Vec::with_capacity(e.size as usize);
            flate2::read::DeflateDecoder::new(raw)
                .read_to_end(&mut out)
                .map_err(|err| format!("entry `{}`: {err}", e.name))?;
            out
        }
        m => {
            return Err(format!(
                "entry `{}` uses compression method {m} (stored and deflate are read)",
                e.name
            ))
        }
    };
    let mut crc = flate2::Crc::new();
    crc.update(&data);
    if data.len() as u64 != e.size || crc.sum() != e.crc {
        return Err(format!(
            "entry `{}` is damaged (size or CRC-32 does not match)",
            e.name
        ));
    }
    Ok((e.name, data))
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
        assert_eq!(
            entries(&zip).unwrap_err(),
            "entry `a.npy` is damaged (size or CRC-32 does not match)"
        );
        let zip = write(&[("a.npy", b"hello".to_vec())], false);
        assert!(entries(&zip[..zip.len() - 30]).is_err());
    }
}
