//! `.npz` archives (what NumPy's `savez` writes and `numpy.load` reads): a ZIP file of `.npy`
//! arrays, one per name, here stored without compression. Arrays are float64, int64 or
//! fixed-width unicode strings, of any number of dimensions (a 0-d array holds one scalar).
//! The archive has no timestamps (every entry is dated 1980-01-01 00:00), so the same arrays
//! give the same bytes.

use std::path::Path;

use crate::error::RunError;
use crate::npy::padded_header;

/// The values of one array, in C order.
#[derive(Clone, Debug, PartialEq)]
pub enum NpyData {
    /// `<f8`: little-endian float64.
    F64(Vec<f64>),
    /// `<i8`: little-endian int64.
    I64(Vec<i64>),
    /// `<Un`: unicode strings, n the longest one's length in characters.
    Text(Vec<String>),
}

impl NpyData {
    /// The number of values.
    pub fn len(&self) -> usize {
        match self {
            Self::F64(v) => v.len(),
            Self::I64(v) => v.len(),
            Self::Text(v) => v.len(),
        }
    }

    /// Whether there is no value.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }
}

/// One named array of an archive: `numpy.load(path)[name]`.
#[derive(Clone, Debug, PartialEq)]
pub struct NpzEntry {
    /// The array's name in the archive (the file is `name.npy`).
    pub name: String,
    /// The shape (empty for a scalar).
    pub shape: Vec<usize>,
    /// The values, as many as the shape's product.
    pub data: NpyData,
}

impl NpzEntry {
    /// A 1-D float64 array.
    pub fn vector(name: impl Into<String>, values: Vec<f64>) -> Self {
        Self { name: name.into(), shape: vec![values.len()], data: NpyData::F64(values) }
    }

    /// A float64 scalar (a 0-d array).
    pub fn scalar(name: impl Into<String>, value: f64) -> Self {
        Self { name: name.into(), shape: Vec::new(), data: NpyData::F64(vec![value]) }
    }

    /// A `rows` × `columns` float64 array from its rows (each of `columns` values).
    pub fn matrix(name: impl Into<String>, rows: &[Vec<f64>], columns: usize) -> Self {
        let values = rows.iter().flatten().copied().collect();
        Self { name: name.into(), shape: vec![rows.len(), columns], data: NpyData::F64(values) }
    }

    /// The `.npy` file of this array; an error if the shape does not hold the values.
    pub fn npy_bytes(&self) -> Result<Vec<u8>, RunError> {
        let count: usize = self.shape.iter().product();
        if count != self.data.len() {
            return Err(RunError::InvalidNpy {
                path: format!("{}.npy", self.name).into(),
                what: format!(
                    "shape {:?} holds {count} values, not {}",
                    self.shape,
                    self.data.len()
                ),
            });
        }
        let descr = match &self.data {
            NpyData::F64(_) => "<f8".to_owned(),
            NpyData::I64(_) => "<i8".to_owned(),
            NpyData::Text(v) => format!("<U{}", text_width(v)),
        };
        let shape = match self.shape.as_slice() {
            [one] => format!("({one},)"),
            dims => {
                format!("({})", dims.iter().map(usize::to_string).collect::<Vec<_>>().join(", "))
            }
        };
        let mut out = padded_header(&format!(
            "'descr': '{descr}', 'fortran_order': False, 'shape': {shape}, "
        ));
        match &self.data {
            NpyData::F64(v) => v.iter().for_each(|x| out.extend_from_slice(&x.to_le_bytes())),
            NpyData::I64(v) => v.iter().for_each(|x| out.extend_from_slice(&x.to_le_bytes())),
            NpyData::Text(v) => {
                let width = text_width(v);
                for text in v {
                    let chars = text.chars().map(u32::from).chain(std::iter::repeat(0));
                    chars.take(width).for_each(|c| out.extend_from_slice(&c.to_le_bytes()));
                }
            }
        }
        Ok(out)
    }
}

/// The characters of the longest string (at least 1, as NumPy's `<U1` for empty strings).
fn text_width(texts: &[String]) -> usize {
    texts.iter().map(|t| t.chars().count()).max().unwrap_or(0).max(1)
}

/// The bytes of an `.npz` archive of `entries` (in order; names must be distinct).
pub fn npz_bytes(entries: &[NpzEntry]) -> Result<Vec<u8>, RunError> {
    let invalid = |what: String| RunError::InvalidNpy { path: "(archive).npz".into(), what };
    let mut out = Vec::new();
    let mut directory = Vec::new();
    for (i, entry) in entries.iter().enumerate() {
        if entries[..i].iter().any(|e| e.name == entry.name) {
            return Err(invalid(format!("two arrays named {:?}", entry.name)));
        }
        let name = format!("{}.npy", entry.name);
        let data = entry.npy_bytes()?;
        let too_large = || invalid(format!("{name}: over 4 GiB (no ZIP64 here)"));
        let size = u32::try_from(data.len()).map_err(|_| too_large())?;
        let offset = u32::try_from(out.len()).map_err(|_| too_large())?;
        let name_length =
            u16::try_from(name.len()).map_err(|_| invalid(format!("{name}: name too long")))?;
        let crc = crc32fast::hash(&data);
        // Version needed 2.0, no flags, stored, time 00:00, date 1980-01-01, CRC, sizes.
        let common = [
            &20u16.to_le_bytes()[..],
            &0u16.to_le_bytes(),
            &0u16.to_le_bytes(),
            &0u16.to_le_bytes(),
            &0x0021u16.to_le_bytes(),
            &crc.to_le_bytes(),
            &size.to_le_bytes(),
            &size.to_le_bytes(),
            &name_length.to_le_bytes(),
        ]
        .concat();
        out.extend_from_slice(&0x0403_4b50u32.to_le_bytes());
        out.extend_from_slice(&common);
        out.extend_from_slice(&0u16.to_le_bytes()); // extra field length
        out.extend_from_slice(name.as_bytes());
        out.extend_from_slice(&data);
        directory.extend_from_slice(&0x0201_4b50u32.to_le_bytes());
        directory.extend_from_slice(&20u16.to_le_bytes()); // made by: version 2.0
        directory.extend_from_slice(&common);
        // Extra, comment lengths, disk number, internal and external attributes.
        directory.extend_from_slice(&[0; 12]);
        directory.extend_from_slice(&offset.to_le_bytes());
        directory.extend_from_slice(name.as_bytes());
    }
    let count = u16::try_from(entries.len()).map_err(|_| invalid("over 65535 arrays".into()))?;
    let too_large = || invalid("over 4 GiB (no ZIP64 here)".into());
    let start = u32::try_from(out.len()).map_err(|_| too_large())?;
    let length = u32::try_from(directory.len()).map_err(|_| too_large())?;
    out.extend_from_slice(&directory);
    out.extend_from_slice(&0x0605_4b50u32.to_le_bytes());
    out.extend_from_slice(&[0; 4]); // this disk, the directory's disk
    out.extend_from_slice(&count.to_le_bytes());
    out.extend_from_slice(&count.to_le_bytes());
    out.extend_from_slice(&length.to_le_bytes());
    out.extend_from_slice(&start.to_le_bytes());
    out.extend_from_slice(&0u16.to_le_bytes()); // comment length
    Ok(out)
}

/// Writes `entries` as the `.npz` archive `path` (atomically, as [`crate::replace_file`]).
pub fn write_npz(path: &Path, entries: &[NpzEntry]) -> Result<(), RunError> {
    let bytes = npz_bytes(entries).map_err(|e| match e {
        RunError::InvalidNpy { what, .. } => RunError::InvalidNpy { path: path.into(), what },
        other => other,
    })?;
    crate::replace_file(path, &bytes)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The little-endian u32 at `at`.
    fn u32_at(bytes: &[u8], at: usize) -> u32 {
        u32::from_le_bytes([bytes[at], bytes[at + 1], bytes[at + 2], bytes[at + 3]])
    }

    /// The dictionary of an `.npy` file and where its data start.
    fn dictionary(npy: &[u8]) -> (String, usize) {
        let start = 10 + u16::from_le_bytes([npy[8], npy[9]]) as usize;
        (String::from_utf8_lossy(&npy[10..start]).into_owned(), start)
    }

    #[test]
    fn npy_headers_are_numpy_s_and_aligned() -> Result<(), RunError> {
        let scalar = NpzEntry::scalar("c", 2.5).npy_bytes()?;
        let (text, start) = dictionary(&scalar);
        assert!(text.starts_with("{'descr': '<f8', 'fortran_order': False, 'shape': (), }"));
        assert!(text.ends_with(" \n"), "{text:?}");
        assert_eq!(start % 64, 0);
        assert_eq!(&scalar[start..], &2.5f64.to_le_bytes());
        let vector = NpzEntry::vector("v", vec![1.0, 2.0]).npy_bytes()?;
        assert!(dictionary(&vector).0.contains("'shape': (2,), }"));
        let axes = NpzEntry {
            name: "axis".into(),
            shape: vec![2],
            data: NpyData::Text(vec!["Y".into(), "Zx".into()]),
        };
        let bytes = axes.npy_bytes()?;
        let (text, start) = dictionary(&bytes);
        assert!(text.contains("'descr': '<U2'"));
        assert_eq!(&bytes[start..], &[89, 0, 0, 0, 0, 0, 0, 0, 90, 0, 0, 0, 120, 0, 0, 0]);
        Ok(())
    }

    #[test]
    fn a_shape_that_does_not_hold_the_values_is_refused() {
        let bad = NpzEntry { name: "m".into(), shape: vec![2, 2], data: NpyData::I64(vec![1; 3]) };
        let error = bad.npy_bytes().expect_err("3 values in a 2 × 2 shape");
        assert!(error.to_string().contains("m.npy"), "{error}");
        let twice = [NpzEntry::scalar("a", 1.0), NpzEntry::scalar("a", 2.0)];
        assert!(npz_bytes(&twice).is_err());
    }

    #[test]
    fn the_archive_lists_each_array_with_its_crc_and_offset() -> Result<(), RunError> {
        let entries = [
            NpzEntry::vector("x", vec![1.0, -1.0, 0.5]),
            NpzEntry::matrix("all/m", &[vec![1.0, 2.0], vec![3.0, 4.0]], 2),
        ];
        let bytes = npz_bytes(&entries)?;
        assert_eq!(npz_bytes(&entries)?, bytes, "deterministic");
        let end = bytes.len() - 22;
        assert_eq!(u32_at(&bytes, end), 0x0605_4b50);
        assert_eq!(u16::from_le_bytes([bytes[end + 10], bytes[end + 11]]), 2);
        let mut at = u32_at(&bytes, end + 16) as usize;
        for entry in &entries {
            assert_eq!(u32_at(&bytes, at), 0x0201_4b50);
            let offset = u32_at(&bytes, at + 42) as usize;
            let size = u32_at(&bytes, at + 20) as usize;
            let name_length = u16::from_le_bytes([bytes[at + 28], bytes[at + 29]]) as usize;
            assert_eq!(
                &bytes[at + 46..at + 46 + name_length],
                format!("{}.npy", entry.name).as_bytes()
            );
            assert_eq!(u32_at(&bytes, offset), 0x0403_4b50);
            let data = &bytes[offset + 30 + name_length..offset + 30 + name_length + size];
            assert_eq!(data, entry.npy_bytes()?.as_slice());
            assert_eq!(u32_at(&bytes, at + 16), crc32fast::hash(data));
            at += 46 + name_length;
        }
        Ok(())
    }
}
