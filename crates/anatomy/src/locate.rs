//! Finding a field's value in RON source text, so that a value rejected after parsing can
//! still be reported as `file:line:column`.
//!
//! The search runs over the text with comments blanked out and string contents skipped, so
//! a field name mentioned in a comment or a string is never taken for the field itself.

use std::path::Path;

use crate::error::{Field, Origin};

/// The origin of `field`'s value in `source` (the element itself for an array element),
/// or just the file when the field cannot be found (e.g. a defaulted field).
pub(crate) fn locate(source: &str, path: &Path, field: &Field) -> Origin {
    let code = code_chars(source);
    match find_value(&code, field) {
        Some(offset) => position(source, path, offset),
        None => Origin::File(path.to_path_buf()),
    }
}

/// The origin of the value of the first `key` whose value is the text `literal` (a string as
/// the file writes it, quotes included), or just the file when no `key` has it: a key that
/// several kinds of field share (`file`) is found by what it says, not by its count.
pub(crate) fn locate_literal(source: &str, path: &Path, key: &str, literal: &str) -> Origin {
    let code = code_chars(source);
    (0..)
        .map_while(|occurrence| find_key(&code, key, occurrence))
        .filter_map(|at| code.get(at).map(|&(offset, _)| offset))
        .find(|&offset| source.get(offset..).is_some_and(|rest| rest.starts_with(literal)))
        .map_or_else(|| Origin::File(path.to_path_buf()), |offset| position(source, path, offset))
}

/// The origin of byte `offset` of `source`: 1-based line, 1-based column in characters.
pub(crate) fn position(source: &str, path: &Path, offset: usize) -> Origin {
    let before = source.get(..offset).unwrap_or(source);
    let line_start = before.rfind('\n').map_or(0, |i| i + 1);
    Origin::Position {
        path: path.to_path_buf(),
        line: 1 + before.matches('\n').count(),
        column: 1 + before[line_start..].chars().count(),
    }
}

/// `(byte offset, char)` of the text outside comments; a comment becomes one space, a
/// string keeps only its quotes.
fn code_chars(source: &str) -> Vec<(usize, char)> {
    let mut out = Vec::with_capacity(source.len());
    let mut chars = source.char_indices().peekable();
    while let Some((i, c)) = chars.next() {
        let next = chars.peek().map(|&(_, n)| n);
        match (c, next) {
            ('/', Some('/')) => {
                out.push((i, ' '));
                while chars.next_if(|&(_, n)| n != '\n').is_some() {}
            }
            ('/', Some('*')) => {
                out.push((i, ' '));
                chars.next();
                skip_block_comment(&mut chars);
            }
            ('"', _) => {
                out.push((i, c));
                let mut escaped = false;
                for (j, s) in chars.by_ref() {
                    if !escaped && s == '"' {
                        out.push((j, s));
                        break;
                    }
                    escaped = !escaped && s == '\\';
                }
            }
            _ => out.push((i, c)),
        }
    }
    out
}

/// Skips a (possibly nested) block comment whose opening `/*` was consumed.
fn skip_block_comment(chars: &mut std::iter::Peekable<std::str::CharIndices<'_>>) {
    let mut depth = 1usize;
    while let Some((_, c)) = chars.next() {
        match (c, chars.peek().map(|&(_, n)| n)) {
            ('*', Some('/')) => {
                chars.next();
                depth -= 1;
                if depth == 0 {
                    return;
                }
            }
            ('/', Some('*')) => {
                chars.next();
                depth += 1;
            }
            _ => {}
        }
    }
}

/// Byte offset of the value of `field` (or of its element) in the filtered text.
fn find_value(code: &[(usize, char)], field: &Field) -> Option<usize> {
    let value = find_key(code, field.key(), field.occurrence)?;
    let Some(index) = field.index else {
        return code.get(value).map(|&(offset, _)| offset);
    };
    let element = find_element(code, value, index).unwrap_or(value);
    code.get(element).map(|&(offset, _)| offset)
}

/// Index (into `code`) of the first non-blank character after the `occurrence`-th `key:` or
/// `key(` (a field or a tuple variant), where `key` is a whole identifier.
fn find_key(code: &[(usize, char)], key: &str, occurrence: usize) -> Option<usize> {
    let key: Vec<char> = key.chars().collect();
    let is_ident = |c: char| c.is_alphanumeric() || c == '_';
    (0..code.len())
        .filter_map(|start| {
            let end = start + key.len();
            let matches = code.get(start..end)?.iter().map(|&(_, c)| c).eq(key.iter().copied());
            let boundary = start == 0 || !is_ident(code[start - 1].1);
            if !(matches && boundary) {
                return None;
            }
            let after = skip_blanks(code, end);
            matches!(code.get(after)?.1, ':' | '(').then(|| skip_blanks(code, after + 1))
        })
        .nth(occurrence)
}

/// Index of element `index` of the array whose `[` is at `open`.
fn find_element(code: &[(usize, char)], open: usize, index: usize) -> Option<usize> {
    if code.get(open)?.1 != '[' {
        return None;
    }
    let mut depth = 0usize;
    let mut element = 0usize;
    let mut at = skip_blanks(code, open + 1);
    while let Some(&(_, c)) = code.get(at) {
        if depth == 0 && element == index && !matches!(c, ']' | ',') {
            return Some(at);
        }
        match c {
            '[' | '(' | '{' => depth += 1,
            ']' | ')' | '}' if depth == 0 => return None,
            ']' | ')' | '}' => depth -= 1,
            ',' if depth == 0 => element += 1,
            _ => {}
        }
        at = skip_blanks(code, at + 1);
    }
    None
}

/// The first index at or after `at` that is not whitespace.
fn skip_blanks(code: &[(usize, char)], at: usize) -> usize {
    code.get(at..)
        .and_then(|rest| rest.iter().position(|&(_, c)| !c.is_whitespace()))
        .map_or(code.len(), |k| at + k)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn at(source: &str, field: Field) -> Option<(usize, usize)> {
        match locate(source, Path::new("f.ron"), &field) {
            Origin::Position { line, column, .. } => Some((line, column)),
            _ => None,
        }
    }

    #[test]
    fn a_shared_key_is_found_by_its_string_value() {
        let source = "(\n  knot: Planned((file: \"plan.ron\")),\n  // file: \"modes.csv\"\n  \
                      force_space: Modes((file: \"modes.csv\", modes: 4)),\n)";
        let at = |literal: &str| match locate_literal(source, Path::new("f.ron"), "file", literal) {
            Origin::Position { line, column, .. } => Some((line, column)),
            _ => None,
        };
        assert_eq!(at("\"modes.csv\""), Some((4, 29)), "not the comment, not the plan's");
        assert_eq!(at("\"plan.ron\""), Some((2, 24)));
        assert_eq!(at("\"other.csv\""), None);
    }

    #[test]
    fn finds_scalar_value_and_skips_comments_and_strings() {
        let src = "(\n  // mass_g: 1\n  name: \"mass_g: 2\",\n  mass_g : 3,\n)";
        assert_eq!(at(src, Field::whole("mass_g")), Some((4, 12)));
    }

    #[test]
    fn finds_array_element_and_nested_key() {
        let src = "(\n  c: [1.0, /* x, y */ 2.0,\n 3.0],\n  t: Some(T(tip: 0.3)),\n)";
        assert_eq!(at(src, Field::element("c", 0)), Some((2, 7)));
        assert_eq!(at(src, Field::element("c", 1)), Some((2, 23)));
        assert_eq!(at(src, Field::element("c", 2)), Some((3, 2)));
        assert_eq!(at(src, Field::whole("t.tip")), Some((4, 18)));
    }

    #[test]
    fn missing_field_or_element_falls_back() {
        let src = "(c: [1.0])";
        assert_eq!(at(src, Field::whole("d")), None);
        assert_eq!(at(src, Field::element("c", 5)), Some((1, 5)));
        assert_eq!(at(src, Field::whole("cc")), None);
    }

    #[test]
    fn identifier_boundary_is_respected() {
        let src = "(xmass_g: 1, mass_g: 2)";
        assert_eq!(at(src, Field::whole("mass_g")), Some((1, 22)));
    }
}
