//! The one reader of a run directory's CSV files (`metrics.csv`, `centreline.csv`,
//! `contacts.csv`, `forces.csv`), built on the `csv` crate: a header line of column names,
//! then rows; quoted fields (a phase name with a comma) are read as the crate reads them.
//! Every error names the file and the 1-based line. The report, `hagfish knot` and the
//! benchmarks' run readers all read through it.
//!
//! The rows are streamed, one at a time through one reused record: a 10 000-body run of
//! 20 s writes a `forces.csv` of ≈ 300 MB, which read whole would be the largest allocation
//! of the process (measured: peak RSS 572 MB when the report read its files whole, against
//! ≈ 80 MB while the run stepped).

use std::collections::VecDeque;
use std::fs::File;
use std::io::{Read, Seek, SeekFrom};
use std::ops::ControlFlow;
use std::path::{Path, PathBuf};

use csv::StringRecord;

use crate::error::ReportError;

/// Bytes read from the file at a time.
const READ_BUFFER_BYTES: usize = 1 << 20;

/// A CSV file whose header has been read into column names; its rows are read by
/// [`CsvFile::rows`] (or [`CsvFile::for_each_record`]).
#[derive(Debug)]
pub struct CsvFile {
    path: PathBuf,
    header: Vec<String>,
}

/// The rows of a [`CsvFile`], read one at a time by [`Rows::next_record`].
pub struct Rows<'a> {
    file: &'a CsvFile,
    reader: csv::Reader<Newlines<File>>,
    /// The newlines before the rows read so far (the `csv` crate's own line count skips
    /// blank lines and `\r\n`).
    newlines: usize,
    /// Where the file ends if it ends in a cut row (see [`Rows::next_record`]).
    cut_at: Option<u64>,
    record: StringRecord,
}

/// One row of a [`CsvFile`].
#[derive(Debug)]
pub struct Record<'a> {
    file: &'a CsvFile,
    line: usize,
    fields: &'a StringRecord,
}

impl CsvFile {
    /// Opens `path` and reads its header (a leading UTF-8 byte order mark is dropped); an
    /// empty file or a blank first line is an error.
    pub fn open(path: &Path) -> Result<Self, ReportError> {
        let (mut reader, _) = reader(path)?;
        let mut first = StringRecord::new();
        let read = reader.read_record(&mut first).map_err(|e| csv_error(path, &e))?;
        let names = first.iter().enumerate();
        let header: Vec<String> = names
            .map(|(k, name)| if k == 0 { name.trim_start_matches('\u{feff}') } else { name })
            .map(|name| name.trim().to_owned())
            .collect();
        if !read || first.position().is_some_and(|p| p.line() != 1) || header.concat().is_empty() {
            let what = "no header line".into();
            return Err(ReportError::Parse { path: path.to_path_buf(), line: 1, what });
        }
        Ok(Self { path: path.to_path_buf(), header })
    }

    /// The file's path.
    pub fn path(&self) -> &Path {
        &self.path
    }

    /// The column names.
    pub fn header(&self) -> &[String] {
        &self.header
    }

    /// The index of the column `name`.
    pub fn column(&self, name: &str) -> Result<usize, ReportError> {
        self.header.iter().position(|h| h == name).ok_or_else(|| ReportError::Parse {
            path: self.path.clone(),
            line: 1,
            what: format!("no column {name:?} in the header"),
        })
    }

    /// The rows, read again from the file's start, after the header.
    pub fn rows(&self) -> Result<Rows<'_>, ReportError> {
        let (reader, cut_at) = reader(&self.path)?;
        let mut rows =
            Rows { file: self, reader, newlines: 0, cut_at, record: StringRecord::new() };
        rows.next_record()?;
        Ok(rows)
    }

    /// Calls `each` on the rows in order, stopping at the first error it returns (see
    /// [`Rows::next_record`] for what is a row).
    pub fn for_each_record(
        &self,
        mut each: impl FnMut(&Record<'_>) -> Result<(), ReportError>,
    ) -> Result<(), ReportError> {
        self.scan(|record| each(record).map(|()| ControlFlow::Continue(())))
    }

    /// [`CsvFile::for_each_record`] that also stops, without error, when `each` breaks.
    pub fn scan(
        &self,
        mut each: impl FnMut(&Record<'_>) -> Result<ControlFlow<()>, ReportError>,
    ) -> Result<(), ReportError> {
        let mut rows = self.rows()?;
        while let Some(record) = rows.next_record()? {
            if each(&record)?.is_break() {
                break;
            }
        }
        Ok(())
    }

    /// The number of rows, each checked as [`Rows::next_record`] does.
    pub fn count_records(&self) -> Result<usize, ReportError> {
        let mut count = 0;
        self.for_each_record(|_| {
            count += 1;
            Ok(())
        })?;
        Ok(count)
    }
}

impl Rows<'_> {
    /// The next row, or `None` at the end. Empty lines are skipped; a row with a different
    /// number of fields from the header is an error. A last row without its newline is left
    /// out: `hagfish run` ends every row with one, so it is a row that a killed run was
    /// writing (Linux stops a write between pages when SIGKILL arrives, so even one `write`
    /// per frame can leave part of a row).
    pub fn next_record(&mut self) -> Result<Option<Record<'_>>, ReportError> {
        let path = &self.file.path;
        if !self.reader.read_record(&mut self.record).map_err(|e| csv_error(path, &e))? {
            return Ok(None);
        }
        if self.cut_at.is_some_and(|end| self.reader.position().byte() >= end) {
            return Ok(None);
        }
        let start = self.record.position().map_or(0, csv::Position::byte);
        let end = self.reader.position().byte();
        let source = self.reader.get_mut();
        self.newlines += source.take_below(start);
        // The newlines from the row's start (with the blank lines before it) to its end:
        // those of blank lines, those inside quoted fields and its own.
        let spanned = source.take_below(end);
        let quoted: usize = self.record.iter().map(|f| f.matches('\n').count()).sum();
        let line = self.newlines + spanned.saturating_sub(quoted + 1) + 1;
        self.newlines += spanned;
        let width = self.file.header.len();
        if self.record.len() != width {
            let what = format!("{} fields where the header has {width}", self.record.len());
            return Err(ReportError::Parse { path: path.clone(), line, what });
        }
        Ok(Some(Record { file: self.file, line, fields: &self.record }))
    }
}

impl Record<'_> {
    /// The row's line in the file (1-based; the header is line 1).
    pub fn line(&self) -> usize {
        self.line
    }

    /// The field in column `index` as text, exactly as written (a phase name may begin or end
    /// with white space, or be one newline).
    pub fn text(&self, index: usize) -> &str {
        self.fields.get(index).unwrap_or_default()
    }

    /// The field in column `index` as a finite number.
    pub fn number(&self, index: usize) -> Result<f64, ReportError> {
        self.optional(index)?.ok_or_else(|| self.error(index, "is empty"))
    }

    /// The field in column `index` as a finite number, or `None` if it is empty.
    pub fn optional(&self, index: usize) -> Result<Option<f64>, ReportError> {
        let field = self.text(index).trim();
        if field.is_empty() {
            return Ok(None);
        }
        match field.parse::<f64>() {
            Ok(v) if v.is_finite() => Ok(Some(v)),
            _ => Err(self.error(index, "is not a finite number")),
        }
    }

    /// The field in column `index` as a non-negative integer.
    pub fn index(&self, index: usize) -> Result<usize, ReportError> {
        let field = self.text(index).trim();
        field.parse().map_err(|_| self.error(index, "is not a non-negative integer"))
    }

    /// An error about column `index` of this row: its name, its text and `what`.
    pub fn error(&self, index: usize, what: &str) -> ReportError {
        let name = self.file.header.get(index).map_or("", String::as_str);
        ReportError::Parse {
            path: self.file.path.clone(),
            line: self.line,
            what: format!("field {} `{name}` ({:?}) {what}", index + 1, self.text(index)),
        }
    }
}

/// A reader of `path` with flexible row widths (checked by [`Rows::next_record`], to say
/// so in this crate's words) and no header handling (read by [`CsvFile::open`]), and where
/// the file ends if its last byte is not a newline (the end of a cut row), else `None`.
fn reader(path: &Path) -> Result<(csv::Reader<Newlines<File>>, Option<u64>), ReportError> {
    let read_error = |source| ReportError::Read { path: path.to_path_buf(), source };
    let mut file = File::open(path).map_err(read_error)?;
    let metadata = file.metadata().map_err(read_error)?;
    if !metadata.is_file() {
        let what = "not a regular file (a device, FIFO, socket or directory); give a file";
        return Err(read_error(std::io::Error::other(what)));
    }
    let length = metadata.len();
    let mut last = [b'\n'];
    if length > 0 {
        file.seek(SeekFrom::End(-1)).map_err(read_error)?;
        file.read_exact(&mut last).map_err(read_error)?;
        file.seek(SeekFrom::Start(0)).map_err(read_error)?;
    }
    let reader = csv::ReaderBuilder::new()
        .has_headers(false)
        .flexible(true)
        .buffer_capacity(READ_BUFFER_BYTES)
        .from_reader(Newlines { inner: file, read: 0, at: VecDeque::new(), line_start: 0 });
    Ok((reader, (last[0] != b'\n').then_some(length)))
}

/// A reader that notes where its newlines are, until [`Newlines::take_below`] counts them
/// (at most the `csv` reader's buffer ahead of the rows read).
struct Newlines<R> {
    inner: R,
    read: u64,
    at: VecDeque<u64>,
    /// Where the line being read starts (after the last newline read).
    line_start: u64,
}

/// The longest line a CSV file may have: 16 MiB (a `centreline.csv` row is < 100 bytes; a
/// file without line breaks is not a CSV file of a run, and would be held whole).
pub const MAX_LINE_BYTES: u64 = 16 << 20;

impl<R> Newlines<R> {
    /// The number of noted newlines before byte `end`, forgotten.
    fn take_below(&mut self, end: u64) -> usize {
        let count = self.at.partition_point(|&at| at < end);
        self.at.drain(..count);
        count
    }
}

impl<R: Read> Read for Newlines<R> {
    fn read(&mut self, buffer: &mut [u8]) -> std::io::Result<usize> {
        let count = self.inner.read(buffer)?;
        let found = buffer[..count].iter().enumerate().filter(|(_, b)| **b == b'\n');
        self.at.extend(found.map(|(i, _)| self.read + i as u64));
        let last = buffer[..count].iter().rposition(|b| *b == b'\n');
        if let Some(i) = last {
            self.line_start = self.read + i as u64 + 1;
        }
        self.read += count as u64;
        if self.read - self.line_start > MAX_LINE_BYTES {
            return Err(std::io::Error::other(format!(
                "a line longer than {MAX_LINE_BYTES} bytes, from byte {}: not a CSV file",
                self.line_start
            )));
        }
        Ok(count)
    }
}

/// `path`'s error from the `csv` crate, at its line where it has one.
fn csv_error(path: &Path, error: &csv::Error) -> ReportError {
    let line = error.position().map_or(0, |p| p.line() as usize);
    ReportError::Parse { path: path.to_path_buf(), line, what: error.to_string() }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::test_files::write;

    #[test]
    fn a_device_or_a_line_without_end_is_refused_not_read_whole() {
        let error = CsvFile::open(Path::new("/dev/zero")).err().map(|e| e.to_string());
        assert!(error.as_deref().is_some_and(|e| e.contains("not a regular file")), "{error:?}");
        let endless = "a,b\n".to_owned() + &"7".repeat(MAX_LINE_BYTES as usize + 10);
        let path = write("endless.csv", &endless);
        let file = CsvFile::open(&path).expect("the header is read");
        let error = file.for_each_record(|_| Ok(())).expect_err("an endless line");
        assert!(error.to_string().contains("a line longer than 16777216 bytes"), "{error}");
        let _ = std::fs::remove_file(path);
    }

    #[test]
    fn reads_numbers_empty_fields_and_names_the_line_of_a_bad_one() {
        let path = write("a.csv", "a, b\r\n1,\r\n\n2.5 ,x\n");
        let file = CsvFile::open(&path).expect("open");
        let (a, b) = (file.column("a").expect("a"), file.column("b").expect("b"));
        let mut seen = Vec::new();
        let error = file
            .for_each_record(|record| {
                seen.push(record.number(a)?);
                if seen.len() == 1 {
                    assert_eq!(record.optional(b)?, None, "an empty field before \\r\\n");
                    return Ok(());
                }
                record.number(b).map(|_| ())
            })
            .expect_err("x is not a number");
        assert_eq!(seen, [1.0, 2.5]);
        assert!(error.to_string().contains("a.csv:4:"), "{error}");
        assert!(file.column("c").is_err());
        assert_eq!(file.count_records().expect("count"), 2, "the blank line is skipped");
    }

    #[test]
    fn quoted_fields_a_byte_order_mark_and_crlf_endings() {
        let path = write("q.csv", "\u{feff}frame,phase\r\n1,\"a,b\"\r\n2,\"say \"\"hi\"\"\"\r\n");
        let file = CsvFile::open(&path).expect("open");
        assert_eq!(file.header(), ["frame", "phase"]);
        let mut phases = Vec::new();
        file.for_each_record(|record| {
            phases.push(record.text(1).to_owned());
            Ok(())
        })
        .expect("rows");
        assert_eq!(phases, ["a,b", "say \"hi\""]);
    }

    #[test]
    fn lines_count_blank_lines_and_quoted_newlines() {
        let path = write("l.csv", "a,b\n\n1,\"x\ny\"\r\n\r\n2,3,4\n");
        let error = CsvFile::open(&path).expect("open").count_records().expect_err("3 fields");
        assert!(error.to_string().contains("l.csv:6: 3 fields where the header has 2"), "{error}");
    }

    #[test]
    fn a_last_line_without_its_newline_is_a_cut_row_and_left_out() {
        let path = write("cut.csv", "a,b\n1,2\n3");
        let file = CsvFile::open(&path).expect("open");
        assert_eq!(file.count_records().expect("count"), 1);
    }

    #[test]
    fn a_short_line_is_an_error_at_its_line() {
        let path = write("b.csv", "a,b\n1,2\n3\n");
        let file = CsvFile::open(&path).expect("open");
        let error = file.count_records().expect_err("a short line");
        assert!(error.to_string().contains("b.csv:3:"), "{error}");
    }

    #[test]
    fn an_empty_file_or_a_blank_header_is_an_error() {
        for (name, text) in [("empty.csv", ""), ("blank.csv", "  \n1,2\n")] {
            let error = CsvFile::open(&write(name, text)).expect_err(name).to_string();
            assert!(error.contains(&format!("{name}:1: no header line")), "{error}");
        }
    }
}
