//! The one writer of CSV text fields and records: the `csv` crate quotes each field where
//! RFC 4180 asks (a comma, quote or line break inside; quotes doubled), so a user's name like
//! `a,b` stays one field. The run's CSV files (a phase's name) and a sweep's `summary.csv`
//! write through it.

use std::fmt;

/// `fields` as one CSV record ending in `\n`, quoted by the `csv` crate where needed. (A
/// record of one empty field is written `""`, so that it is not an empty line.)
pub fn csv_record<T: AsRef<[u8]>>(fields: impl IntoIterator<Item = T>) -> String {
    let mut writer =
        csv::WriterBuilder::new().terminator(csv::Terminator::Any(b'\n')).from_writer(Vec::new());
    // Writing into memory fails only on a field that is not UTF-8 text, which `&str` rules out.
    let written = writer.write_record(fields).ok().and_then(|()| writer.into_inner().ok());
    String::from_utf8_lossy(&written.unwrap_or_default()).into_owned()
}

/// A text field of a CSV row, quoted only when it must be ([`csv_record`]).
#[derive(Clone, Copy, Debug)]
pub(crate) struct CsvText<'a>(pub(crate) &'a str);

impl fmt::Display for CsvText<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.0.is_empty() {
            return Ok(());
        }
        let record = csv_record([self.0]);
        f.write_str(record.strip_suffix('\n').unwrap_or(&record))
    }
}

#[cfg(test)]
mod tests {
    use super::{CsvText, csv_record};

    #[test]
    fn a_record_quotes_only_the_fields_that_need_it() {
        assert_eq!(csv_record(["a,b", "", "x", "say \"hi\""]), "\"a,b\",,x,\"say \"\"hi\"\"\"\n");
        assert_eq!(csv_record(["cr\r"]), "\"cr\r\"\n", "a carriage return too");
    }

    #[test]
    fn plain_names_stay_as_they_are_and_others_are_quoted() {
        assert_eq!(CsvText("slide").to_string(), "slide");
        assert_eq!(CsvText("").to_string(), "");
        assert_eq!(CsvText("a,b").to_string(), "\"a,b\"");
        assert_eq!(CsvText("say \"hi\"").to_string(), "\"say \"\"hi\"\"\"");
        assert_eq!(CsvText("two\nlines").to_string(), "\"two\nlines\"");
    }

    #[test]
    fn a_quoted_field_reads_back_as_one_field_with_its_text() {
        for name in ["a,b", "say \"hi\", then", "x\r\ny", "plain"] {
            let row = format!("1,{},2\n", CsvText(name));
            let mut reader =
                csv::ReaderBuilder::new().has_headers(false).from_reader(row.as_bytes());
            let record = reader.records().next().expect("a row").expect("well formed");
            assert_eq!(record.len(), 3, "{row:?}");
            assert_eq!(&record[1], name);
        }
    }
}
