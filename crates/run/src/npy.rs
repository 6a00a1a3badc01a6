//! `.npy` arrays (NumPy format 1.0) of f64 rows, written one row per frame.
//!
//! The header has a fixed length of [`HEADER_BYTES`] with the row count right-aligned in a
//! 20-character field, so it is rewritten in place after each row: the row is written and
//! flushed first, then the header's count, so a file cut short by a killed run is always a
//! valid array of the rows counted in its header (a row being written when the run was killed
//! lies beyond them and is ignored by NumPy's `load`, which reads as many values as the shape
//! says, and by [`read_npy`]).

use std::path::Path;

use crate::error::RunError;
use crate::output_file::OutputFile;

/// Length of the header (magic, version, header length and the padded dictionary).
pub const HEADER_BYTES: usize = 128;

/// The header of a little-endian f64 C-order array of `rows` × `columns` (the row count
/// right-aligned in 20 characters, so that the header keeps its length as rows are added).
fn header(rows: usize, columns: usize) -> Vec<u8> {
    padded_header(&format!(
        "'descr': '<f8', 'fortran_order': False, 'shape': ({rows:>20}, {columns}), "
    ))
}

/// The NPY 1.0 header of the dictionary `entries` (`{entries}`, without the braces): magic,
/// version, header length and the dictionary padded with spaces and a newline to a multiple
/// of 64 bytes, as NumPy writes it.
pub(crate) fn padded_header(entries: &str) -> Vec<u8> {
    let dictionary = format!("{{{entries}}}");
    let length = (10 + dictionary.len() + 1).div_ceil(64) * 64;
    let mut out = Vec::with_capacity(length);
    out.extend_from_slice(b"\x93NUMPY\x01\x00");
    out.extend_from_slice(&((length - 10) as u16).to_le_bytes());
    out.extend_from_slice(dictionary.as_bytes());
    out.resize(length - 1, b' ');
    out.push(b'\n');
    out
}

/// FNV-1a 64's offset basis: the hash of no bytes ([`hagfish_sim::fnv1a64`]'s).
const FNV_OFFSET: u64 = 0xcbf2_9ce4_8422_2325;

/// `hash` (FNV-1a 64, as [`hagfish_sim::fnv1a64`]) continued over `bytes`.
fn fnv_extend(hash: u64, bytes: &[u8]) -> u64 {
    bytes.iter().fold(hash, |hash, &b| (hash ^ u64::from(b)).wrapping_mul(0x100_0000_01b3))
}

/// An `.npy` file of f64 rows of a fixed width, growing by one row at a time, with the FNV-1a
/// 64 hash of its rows' bytes so far (the checkpoint records it; a resume checks it).
#[derive(Debug)]
pub(crate) struct NpyWriter {
    file: OutputFile,
    columns: usize,
    rows: usize,
    buffer: Vec<u8>,
    hash: u64,
}

/// The FNV-1a 64 hash of the first `rows` rows of `columns` values of the `.npy` file at
/// `path` (its bytes after the header), read a MiB at a time; checked against `expected`
/// (16 hex digits, as a checkpoint records it) when given.
///
/// # Errors
/// [`RunError::Output`] if the file cannot be read or is shorter, [`RunError::ChangedArray`]
/// if the hash is not `expected`.
pub(crate) fn rows_hash(
    path: &Path,
    columns: usize,
    rows: usize,
    expected: Option<&str>,
) -> Result<u64, RunError> {
    use std::io::{Read, Seek, SeekFrom};
    let fail = |source| RunError::Output { path: path.to_path_buf(), source };
    let mut file = std::fs::File::open(path).map_err(fail)?;
    let mut left = 8 * rows as u64 * columns as u64;
    if file.metadata().map_err(fail)?.len() < HEADER_BYTES as u64 + left {
        // Too short: reopening it says so, with the lengths.
        return Ok(FNV_OFFSET);
    }
    file.seek(SeekFrom::Start(HEADER_BYTES as u64)).map_err(fail)?;
    let mut chunk = vec![0u8; 1 << 20];
    let mut hash = FNV_OFFSET;
    while left > 0 {
        let take = left.min(chunk.len() as u64) as usize;
        file.read_exact(&mut chunk[..take]).map_err(fail)?;
        hash = fnv_extend(hash, &chunk[..take]);
        left -= take as u64;
    }
    let found = format!("{hash:016x}");
    match expected {
        Some(expected) if expected != found => {
            Err(RunError::ChangedArray { path: path.to_path_buf(), rows })
        }
        _ => Ok(hash),
    }
}

impl NpyWriter {
    /// Creates the file at `path` with zero rows of `columns` values.
    pub(crate) fn create(path: &Path, columns: usize) -> Result<Self, RunError> {
        let mut file = OutputFile::create(path)?;
        file.bytes(&header(0, columns));
        file.flush()?;
        Ok(Self { file, columns, rows: 0, buffer: Vec::new(), hash: FNV_OFFSET })
    }

    /// Reopens the file at `path`, keeping its first `rows` rows of `columns` values, whose
    /// hash ([`rows_hash`]) is `hash`.
    pub(crate) fn reopen(
        path: &Path,
        columns: usize,
        rows: usize,
        hash: u64,
    ) -> Result<Self, RunError> {
        let length = (HEADER_BYTES + 8 * rows * columns) as u64;
        let mut file = OutputFile::reopen(path, length)?;
        file.overwrite(0, &header(rows, columns))?;
        Ok(Self { file, columns, rows, buffer: Vec::new(), hash })
    }

    /// The FNV-1a 64 hash of the rows written, as 16 hex digits.
    pub(crate) fn rows_hash(&self) -> String {
        format!("{:016x}", self.hash)
    }

    /// Appends one row (`values.len()` must be the width; shorter rows are padded with NaN,
    /// longer ones cut) and updates the header's row count.
    pub(crate) fn append(&mut self, values: &[f64]) -> Result<(), RunError> {
        self.buffer.clear();
        let padded = values.iter().copied().chain(std::iter::repeat(f64::NAN));
        for v in padded.take(self.columns) {
            self.buffer.extend_from_slice(&v.to_le_bytes());
        }
        self.file.bytes(&self.buffer);
        self.file.flush()?;
        self.hash = fnv_extend(self.hash, &self.buffer);
        self.rows += 1;
        self.file.overwrite(0, &header(self.rows, self.columns))
    }

    /// The file's length in bytes.
    pub(crate) fn len(&self) -> u64 {
        self.file.len()
    }

    /// The file's path.
    pub(crate) fn path(&self) -> &Path {
        self.file.path()
    }
}

/// A 2-D f64 array read from an `.npy` file.
#[derive(Clone, Debug, PartialEq)]
pub struct NpyArray {
    /// Number of rows.
    pub rows: usize,
    /// Number of columns.
    pub columns: usize,
    /// The values, row after row.
    pub values: Vec<f64>,
}

/// Reads a 2-D little-endian f64 C-order `.npy` file (format 1.0, as written here). Bytes
/// beyond the rows counted in the header are ignored; fewer bytes than the header counts are
/// an error.
pub fn read_npy(path: &Path) -> Result<NpyArray, RunError> {
    let bytes = std::fs::read(path)
        .map_err(|source| RunError::Output { path: path.to_path_buf(), source })?;
    let invalid = |what: &str| RunError::InvalidNpy { path: path.to_path_buf(), what: what.into() };
    if bytes.len() < 10 || &bytes[..8] != b"\x93NUMPY\x01\x00" {
        return Err(invalid("no NPY 1.0 magic"));
    }
    let length = 10 + u16::from_le_bytes([bytes[8], bytes[9]]) as usize;
    let text = bytes
        .get(10..length)
        .and_then(|h| std::str::from_utf8(h).ok())
        .ok_or_else(|| invalid("truncated header"))?;
    if !text.contains("'descr': '<f8'") || !text.contains("'fortran_order': False") {
        return Err(invalid("not a little-endian f64 C-order array"));
    }
    let shape = text
        .split_once("'shape': (")
        .and_then(|(_, rest)| rest.split_once(')'))
        .map(|(shape, _)| shape)
        .ok_or_else(|| invalid("no shape"))?;
    let dims: Vec<usize> = shape
        .split(',')
        .map(str::trim)
        .filter(|s| !s.is_empty())
        .map(str::parse)
        .collect::<Result<_, _>>()
        .map_err(|_| invalid("shape is not a tuple of integers"))?;
    let [rows, columns] = dims[..] else { return Err(invalid("not a 2-D array")) };
    let data = &bytes[length..];
    if data.len() < 8 * rows * columns {
        return Err(invalid("fewer values than the shape says"));
    }
    let values = data
        .chunks_exact(8)
        .take(rows * columns)
        .map(|c| f64::from_le_bytes([c[0], c[1], c[2], c[3], c[4], c[5], c[6], c[7]]))
        .collect();
    Ok(NpyArray { rows, columns, values })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn header_is_aligned_and_rows_survive_a_reopen() -> Result<(), RunError> {
        assert_eq!(header(123, 150).len(), HEADER_BYTES);
        assert_eq!(HEADER_BYTES % 64, 0);
        let dir = std::env::temp_dir().join(format!("hagfish-npy-{}", std::process::id()));
        std::fs::create_dir_all(&dir)
            .map_err(|source| RunError::Output { path: dir.clone(), source })?;
        let path = dir.join("a.npy");
        let mut writer = NpyWriter::create(&path, 3)?;
        for k in 0..4 {
            writer.append(&[k as f64, -0.0, f64::MIN_POSITIVE])?;
        }
        let read = read_npy(&path)?;
        assert_eq!((read.rows, read.columns), (4, 3));
        assert_eq!(read.values[9].to_bits(), 3f64.to_bits());
        assert_eq!(read.values[1].to_bits(), (-0.0f64).to_bits());
        let four_rows = writer.rows_hash();
        drop(writer);
        assert_eq!(format!("{:016x}", rows_hash(&path, 3, 4, Some(&four_rows))?), four_rows);
        let bytes = std::fs::read(&path)
            .map_err(|source| RunError::Output { path: path.clone(), source })?;
        assert_eq!(four_rows, format!("{:016x}", hagfish_sim::fnv1a64(&bytes[HEADER_BYTES..])));
        let two_rows = rows_hash(&path, 3, 2, None)?;
        let mut writer = NpyWriter::reopen(&path, 3, 2, two_rows)?;
        writer.append(&[7.0, 8.0])?;
        assert_eq!(writer.rows_hash(), format!("{:016x}", rows_hash(&path, 3, 3, None)?));
        let changed = rows_hash(&path, 3, 2, Some("0123456789abcdef")).expect_err("changed");
        let message = changed.to_string();
        assert!(
            message.contains("first 2 rows are not those the checkpoint recorded"),
            "{message}"
        );
        assert!(!message.contains("0123456789abcdef"), "the recorded hash is not shown: {message}");
        let read = read_npy(&path)?;
        assert_eq!((read.rows, read.columns), (3, 3));
        assert_eq!(read.values[6..8], [7.0, 8.0]);
        assert!(read.values[8].is_nan());
        // Bytes of a row cut short beyond the counted rows are ignored.
        let mut bytes = std::fs::read(&path)
            .map_err(|source| RunError::Output { path: path.clone(), source })?;
        bytes.extend_from_slice(&[1, 2, 3]);
        std::fs::write(&path, &bytes)
            .map_err(|source| RunError::Output { path: path.clone(), source })?;
        assert_eq!(read_npy(&path)?.rows, 3);
        drop(writer);
        std::fs::remove_dir_all(&dir).map_err(|source| RunError::Output { path: dir, source })?;
        Ok(())
    }
}
