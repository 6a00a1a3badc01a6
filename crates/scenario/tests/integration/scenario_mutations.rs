//! The scenario loader never panics: `data/scenarios/form.ron` with random byte flips,
//! deletions and insertions either loads or gives an error whose message starts with a
//! position in the file (`path:line:column:`) or names the file.

use std::path::Path;

use hagfish_scenario::LoadedScenario;
use proptest::prelude::*;

const SCENARIO: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../../data/scenarios/form.ron");

/// One edit of the file's bytes, at a position taken modulo the length.
#[derive(Clone, Debug)]
enum Edit {
    Flip { at: usize, bit: u8 },
    Delete { at: usize, length: usize },
    Insert { at: usize, bytes: Vec<u8> },
}

fn edit() -> impl Strategy<Value = Edit> {
    // Inserted bytes favour RON's own punctuation and digits, which get further than noise.
    let byte = prop_oneof![
        any::<u8>(),
        prop::sample::select(b"()[]{},:.-+eE0123456789\"/* \nSomeNoneFormHold".to_vec()),
    ];
    prop_oneof![
        (any::<usize>(), 0u8..8).prop_map(|(at, bit)| Edit::Flip { at, bit }),
        (any::<usize>(), 1usize..16).prop_map(|(at, length)| Edit::Delete { at, length }),
        (any::<usize>(), prop::collection::vec(byte, 1..8))
            .prop_map(|(at, bytes)| Edit::Insert { at, bytes }),
    ]
}

fn apply(bytes: &mut Vec<u8>, edit: &Edit) {
    let at = |i: usize, len: usize| if len == 0 { 0 } else { i % len };
    match edit {
        Edit::Flip { at: i, bit } => {
            let i = at(*i, bytes.len());
            if let Some(b) = bytes.get_mut(i) {
                *b ^= 1 << bit;
            }
        }
        Edit::Delete { at: i, length } => {
            let start = at(*i, bytes.len());
            let end = (start + length).min(bytes.len());
            bytes.drain(start..end);
        }
        Edit::Insert { at: i, bytes: new } => {
            let start = at(*i, bytes.len() + 1);
            bytes.splice(start..start, new.iter().copied());
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 256, ..ProptestConfig::default() })]

    #[test]
    fn mutated_scenarios_load_or_fail_with_a_position(edits in prop::collection::vec(edit(), 1..4)) {
        let mut bytes = std::fs::read(SCENARIO).expect("form.ron is readable");
        for e in &edits {
            apply(&mut bytes, e);
        }
        let path = Path::new(SCENARIO);
        if let Err(e) = LoadedScenario::parse(&bytes, path) {
            let message = e.to_string();
            prop_assert!(message.strip_prefix(SCENARIO).is_some_and(|m| m.starts_with(':')), "{message}");
        }
    }
}
