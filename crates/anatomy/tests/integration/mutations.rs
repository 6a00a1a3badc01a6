//! Robustness: random byte-level damage to the ES103 file never panics the loader or the
//! model builder; every outcome is `Ok` or a typed `Err`.

use std::path::Path;

use hagfish_anatomy::Biometrics;
use proptest::prelude::*;

const ES103: &[u8] = include_bytes!("../../../../data/hagfish/es103.ron");

/// One edit of the file's bytes; positions are reduced modulo the current length.
#[derive(Clone, Debug)]
enum Mutation {
    Replace(usize, u8),
    Delete(usize),
    Insert(usize, u8),
}

impl Mutation {
    fn apply(&self, bytes: &mut Vec<u8>) {
        match *self {
            Mutation::Replace(at, b) if !bytes.is_empty() => {
                let at = at % bytes.len();
                bytes[at] = b;
            }
            Mutation::Delete(at) if !bytes.is_empty() => {
                bytes.remove(at % bytes.len());
            }
            Mutation::Insert(at, b) => bytes.insert(at % (bytes.len() + 1), b),
            _ => {}
        }
    }
}

/// Bytes biased toward RON's own syntax and digits, so that many mutants still parse and
/// reach validation and the model build.
fn byte() -> impl Strategy<Value = u8> {
    prop_oneof![any::<u8>(), prop::sample::select(b"0123456789.-+eE,:()[]\" \n/*".to_vec()),]
}

fn mutation() -> impl Strategy<Value = Mutation> {
    prop_oneof![
        (any::<usize>(), byte()).prop_map(|(at, b)| Mutation::Replace(at, b)),
        any::<usize>().prop_map(Mutation::Delete),
        (any::<usize>(), byte()).prop_map(|(at, b)| Mutation::Insert(at, b)),
    ]
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 512, ..ProptestConfig::default() })]

    #[test]
    fn mutated_file_never_panics(mutations in prop::collection::vec(mutation(), 1..8)) {
        let mut bytes = ES103.to_vec();
        for m in &mutations {
            m.apply(&mut bytes);
        }
        if let Ok(b) = Biometrics::from_ron(&bytes, Path::new("mutant.ron")) {
            // Derivation may still fail (typed) for extreme values; the model is built from
            // the table, so it cannot succeed where the table failed.
            let table = b.body_table();
            let model = b.to_model();
            prop_assert!(table.is_ok() || model.is_err());
            if let Ok(model) = model {
                prop_assert_eq!(model.body_count(), b.body_count);
            }
        }
    }
}
