//! Text fields of the CSV files (a phase's name, which the scenario chooses) written as
//! RFC 4180 asks: as they are when they hold no comma, quote or line break, else between
//! double quotes with every quote doubled — so a name like `a,b` stays one field.

use std::fmt;

/// A text field of a CSV row, quoted only when it must be.
#[derive(Clone, Copy, Debug)]
pub(crate) struct CsvText<'a>(pub(crate) &'a str);

impl fmt::Display for CsvText<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let text = self.0;
        if !text.contains([',', '"', '\n', '\r']) {
            return f.write_str(text);
        }
        f.write_str("\"")?;
        f.write_str(&text.replace('"', "\"\""))?;
        f.write_str("\"")
    }
}

#[cfg(test)]
mod tests {
    use super::CsvText;

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
