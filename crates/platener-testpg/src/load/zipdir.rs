//! The names in a ZIP's central directory: enough to tell a plan download from a broken or
//! truncated one without a ZIP library (the end record, its entry count and every entry's
//! header must be where they claim to be).

/// The end-of-central-directory record's signature and smallest size.
const END_SIG: [u8; 4] = *b"PK\x05\x06";
const END_LEN: usize = 22;
/// A central directory entry's signature and fixed size.
const ENTRY_SIG: [u8; 4] = *b"PK\x01\x02";
const ENTRY_LEN: usize = 46;

fn u16_at(b: &[u8], at: usize) -> Option<usize> {
    Some(usize::from(u16::from_le_bytes(b.get(at..at + 2)?.try_into().ok()?)))
}

fn u32_at(b: &[u8], at: usize) -> Option<usize> {
    usize::try_from(u32::from_le_bytes(b.get(at..at + 4)?.try_into().ok()?)).ok()
}

/// The file names of a ZIP, in directory order; `None` when it is not a whole ZIP.
pub fn names(zip: &[u8]) -> Option<Vec<String>> {
    // The end record is last, followed by a comment of at most 65535 bytes.
    let lowest = zip.len().saturating_sub(END_LEN + 0xFFFF);
    let end = (lowest..=zip.len().checked_sub(END_LEN)?)
        .rev()
        .find(|&i| zip[i..i + 4] == END_SIG && i + END_LEN + u16_at(zip, i + 20).unwrap_or(usize::MAX) == zip.len())?;
    let (count, offset) = (u16_at(zip, end + 10)?, u32_at(zip, end + 16)?);
    let mut names = Vec::with_capacity(count);
    let mut at = offset;
    for _ in 0..count {
        if zip.get(at..at + 4)? != ENTRY_SIG {
            return None;
        }
        let (name_len, extra, comment) = (u16_at(zip, at + 28)?, u16_at(zip, at + 30)?, u16_at(zip, at + 32)?);
        let name = zip.get(at + ENTRY_LEN..at + ENTRY_LEN + name_len)?;
        names.push(String::from_utf8_lossy(name).into_owned());
        at += ENTRY_LEN + name_len + extra + comment;
    }
    (at <= end).then_some(names)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A ZIP of empty stored files with the given names, written by hand.
    fn zip_of(files: &[&str]) -> Vec<u8> {
        let mut out = Vec::new();
        let mut central = Vec::new();
        for name in files {
            let offset = u32::try_from(out.len()).expect("small");
            let n = u16::try_from(name.len()).expect("short");
            out.extend_from_slice(b"PK\x03\x04");
            out.extend_from_slice(&[0; 22]);
            out.extend_from_slice(&n.to_le_bytes());
            out.extend_from_slice(&0u16.to_le_bytes());
            out.extend_from_slice(name.as_bytes());
            central.extend_from_slice(&ENTRY_SIG);
            central.extend_from_slice(&[0; 24]);
            central.extend_from_slice(&n.to_le_bytes());
            central.extend_from_slice(&[0; 12]);
            central.extend_from_slice(&offset.to_le_bytes());
            central.extend_from_slice(name.as_bytes());
        }
        let dir_at = u32::try_from(out.len()).expect("small");
        let dir_len = u32::try_from(central.len()).expect("small");
        out.extend_from_slice(&central);
        out.extend_from_slice(&END_SIG);
        out.extend_from_slice(&[0; 4]);
        let count = u16::try_from(files.len()).expect("few");
        out.extend_from_slice(&count.to_le_bytes());
        out.extend_from_slice(&count.to_le_bytes());
        out.extend_from_slice(&dir_len.to_le_bytes());
        out.extend_from_slice(&dir_at.to_le_bytes());
        out.extend_from_slice(&0u16.to_le_bytes());
        out
    }

    #[test]
    fn names_of_a_whole_zip_and_none_of_a_cut_one() {
        let zip = zip_of(&["plan.json", "sheets/sheet-1.svg"]);
        assert_eq!(
            names(&zip),
            Some(vec!["plan.json".to_string(), "sheets/sheet-1.svg".to_string()])
        );
        assert_eq!(names(&zip_of(&[])), Some(Vec::new()));
        assert_eq!(names(&zip[..zip.len() - 1]), None, "a truncated end record");
        assert_eq!(names(&zip[..zip.len() / 2]), None, "a truncated download");
        assert_eq!(names(b"PK\x03\x04 a fake plan"), None);
        let mut broken = zip.clone();
        let dir_at = broken.len() - 6;
        broken[dir_at] = broken[dir_at].wrapping_add(1);
        assert_eq!(names(&broken), None, "a directory offset off by one");
    }
}
