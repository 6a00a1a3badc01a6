//! A minimal reader of the run directory's CSV files: a header line of column names, then
//! comma-separated fields without quoting (what `hagfish run` writes). Every error names the
//! file and the 1-based line.
//!
//! The data lines are streamed, one at a time through one reused buffer: a 10 000-body run
//! of 20 s writes a `forces.csv` of ≈ 300 MB, which read whole would be the largest
//! allocation of the process (measured: peak RSS 572 MB when the report read its files
//! whole, against ≈ 80 MB while the run stepped).

use std::fs::File;
use std::io::{BufRead, BufReader};
use std::ops::{ControlFlow, Range};
use std::path::{Path, PathBuf};

use crate::error::ReportError;

/// Bytes read from the file at a time.
const READ_BUFFER_BYTES: usize = 1 << 20;

/// A CSV file whose header has been read and split into column names; its data lines are
/// read by [`CsvFile::for_each_record`].
#[derive(Debug)]
pub struct CsvFile {
    path: PathBuf,
    header: Vec<String>,
}

/// One data line of a [`CsvFile`].
#[derive(Debug)]
pub struct Record<'a> {
    path: &'a Path,
    line: usize,
    text: &'a str,
    fields: &'a [Range<usize>],
}

impl CsvFile {
    /// Opens `path` and reads its header; an empty file or a blank first line is an error.
    pub fn open(path: &Path) -> Result<Self, ReportError> {
        let mut reader = Self::reader(path)?;
        let mut first = String::new();
        reader.read_line(&mut first).map_err(|source| Self::read_error(path, source))?;
        if first.trim().is_empty() {
            return Err(ReportError::Parse {
                path: path.to_path_buf(),
                line: 1,
                what: "no header line".into(),
            });
        }
        let header = first.split(',').map(|name| name.trim().to_string()).collect();
        Ok(Self { path: path.to_path_buf(), header })
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

    /// Calls `each` on the data lines in order (blank lines skipped), stopping at the first
    /// error it returns; a line with a different number of fields from the header is an
    /// error. A last line without its newline is left out: `hagfish run` ends every row with
    /// one, so it is a row that a killed run was writing (Linux stops a write between pages
    /// when SIGKILL arrives, so even one `write` per frame can leave part of a row). The file
    /// is read again from its start, a line at a time.
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
        let mut reader = Self::reader(&self.path)?;
        let width = self.header.len();
        let (mut text, mut fields) = (String::new(), Vec::with_capacity(width));
        for line in 1.. {
            text.clear();
            let read = reader
                .read_line(&mut text)
                .map_err(|source| Self::read_error(&self.path, source))?;
            if read == 0 || !text.ends_with('\n') {
                return Ok(());
            }
            if line == 1 || text.trim().is_empty() {
                continue;
            }
            fields.clear();
            let mut start = 0;
            // A byte scan: `,` is ASCII, so every cut falls between characters.
            for (i, byte) in text.bytes().enumerate() {
                if byte == b',' {
                    fields.push(start..i);
                    start = i + 1;
                }
            }
            fields.push(start..text.len());
            if fields.len() != width {
                return Err(ReportError::Parse {
                    path: self.path.clone(),
                    line,
                    what: format!("{} fields where the header has {width}", fields.len()),
                });
            }
            if each(&Record { path: &self.path, line, text: &text, fields: &fields })?.is_break() {
                return Ok(());
            }
        }
        Ok(())
    }

    /// The number of data lines (blank lines skipped), each checked as
    /// [`CsvFile::for_each_record`] does.
    pub fn count_records(&self) -> Result<usize, ReportError> {
        let mut count = 0;
        self.for_each_record(|_| {
            count += 1;
            Ok(())
        })?;
        Ok(count)
    }

    fn reader(path: &Path) -> Result<BufReader<File>, ReportError> {
        let file = File::open(path).map_err(|source| Self::read_error(path, source))?;
        Ok(BufReader::with_capacity(READ_BUFFER_BYTES, file))
    }

    fn read_error(path: &Path, source: std::io::Error) -> ReportError {
        ReportError::Read { path: path.to_path_buf(), source }
    }
}

impl Record<'_> {
    /// The field in column `index` as text (surrounding white space removed).
    pub fn text(&self, index: usize) -> &str {
        self.text[self.fields[index].clone()].trim()
    }

    /// The field in column `index` as a finite number.
    pub fn number(&self, index: usize) -> Result<f64, ReportError> {
        self.optional(index)?.ok_or_else(|| self.error(index, "is empty"))
    }

    /// The field in column `index` as a finite number, or `None` if it is empty.
    pub fn optional(&self, index: usize) -> Result<Option<f64>, ReportError> {
        let field = self.text(index);
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
        self.text(index).parse().map_err(|_| self.error(index, "is not a non-negative integer"))
    }

    /// An error about column `index` of this line.
    pub fn error(&self, index: usize, what: &str) -> ReportError {
        ReportError::Parse {
            path: self.path.to_path_buf(),
            line: self.line,
            what: format!("field {} ({:?}) {what}", index + 1, self.text(index)),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::test_files::write;

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
