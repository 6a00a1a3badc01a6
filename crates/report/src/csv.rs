//! A minimal reader of the run directory's CSV files: a header line of column names, then
//! comma-separated fields without quoting (what `hagfish run` writes). Every error names the
//! file and the 1-based line.

use std::path::{Path, PathBuf};

use crate::error::ReportError;

/// A CSV file read into memory, with its header split into column names.
#[derive(Debug)]
pub struct CsvFile {
    path: PathBuf,
    text: String,
    header: Vec<String>,
}

/// One data line of a [`CsvFile`].
#[derive(Debug)]
pub struct Record<'a> {
    path: &'a Path,
    line: usize,
    fields: Vec<&'a str>,
}

impl CsvFile {
    /// Reads `path`; an empty file (no header) is an error.
    pub fn read(path: &Path) -> Result<Self, ReportError> {
        let text = std::fs::read_to_string(path)
            .map_err(|source| ReportError::Read { path: path.to_path_buf(), source })?;
        let header = text
            .lines()
            .next()
            .filter(|l| !l.trim().is_empty())
            .ok_or_else(|| ReportError::Parse {
                path: path.to_path_buf(),
                line: 1,
                what: "no header line".into(),
            })?
            .split(',')
            .map(|name| name.trim().to_string())
            .collect();
        Ok(Self { path: path.to_path_buf(), text, header })
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

    /// The data lines in order (blank lines skipped); a line with a different number of
    /// fields from the header is an error.
    pub fn records(&self) -> impl Iterator<Item = Result<Record<'_>, ReportError>> {
        let width = self.header.len();
        self.text.lines().enumerate().skip(1).filter(|(_, l)| !l.trim().is_empty()).map(
            move |(i, l)| {
                let mut fields = Vec::with_capacity(width);
                let mut start = 0;
                // A byte scan: `,` is ASCII, so every cut falls between characters.
                for (i, byte) in l.bytes().enumerate() {
                    if byte == b',' {
                        fields.push(l[start..i].trim());
                        start = i + 1;
                    }
                }
                fields.push(l[start..].trim());
                if fields.len() == width {
                    Ok(Record { path: &self.path, line: i + 1, fields })
                } else {
                    Err(ReportError::Parse {
                        path: self.path.clone(),
                        line: i + 1,
                        what: format!("{} fields where the header has {width}", fields.len()),
                    })
                }
            },
        )
    }
}

impl Record<'_> {
    /// The field in column `index` as text.
    pub fn text(&self, index: usize) -> &str {
        self.fields[index]
    }

    /// The field in column `index` as a finite number.
    pub fn number(&self, index: usize) -> Result<f64, ReportError> {
        self.optional(index)?.ok_or_else(|| self.error(index, "is empty"))
    }

    /// The field in column `index` as a finite number, or `None` if it is empty.
    pub fn optional(&self, index: usize) -> Result<Option<f64>, ReportError> {
        let field = self.fields[index];
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
        self.fields[index].parse().map_err(|_| self.error(index, "is not a non-negative integer"))
    }

    /// An error about column `index` of this line.
    pub fn error(&self, index: usize, what: &str) -> ReportError {
        ReportError::Parse {
            path: self.path.to_path_buf(),
            line: self.line,
            what: format!("field {} ({:?}) {what}", index + 1, self.fields[index]),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::test_files::write;

    #[test]
    fn reads_numbers_empty_fields_and_names_the_line_of_a_bad_one() {
        let path = write("a.csv", "a,b\n1,\n\n2.5,x\n");
        let file = CsvFile::read(&path).expect("read");
        let (a, b) = (file.column("a").expect("a"), file.column("b").expect("b"));
        let records: Vec<Record<'_>> = file.records().collect::<Result<_, _>>().expect("rows");
        assert_eq!(records.len(), 2);
        assert_eq!(records[0].number(a).expect("1"), 1.0);
        assert_eq!(records[0].optional(b).expect("empty"), None);
        let message = records[1].number(b).expect_err("x").to_string();
        assert!(message.contains("a.csv:4:"), "{message}");
        assert!(file.column("c").is_err());
    }

    #[test]
    fn a_short_line_is_an_error_at_its_line() {
        let path = write("b.csv", "a,b\n1,2\n3\n");
        let file = CsvFile::read(&path).expect("read");
        let error = file.records().find_map(Result::err).expect("an error");
        assert!(error.to_string().contains("b.csv:3:"), "{error}");
    }
}
