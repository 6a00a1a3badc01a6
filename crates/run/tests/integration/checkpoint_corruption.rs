//! A damaged checkpoint is refused, never resumed from and never a panic: random bit flips,
//! truncations, deletions and insertions of a written `checkpoint.ron` all fail
//! [`Checkpoint::read`] with an error naming the file (the checksum line catches every
//! change, the parser what is left).

use hagfish_control::ControllerState;
use hagfish_run::{
    CHECKPOINT_FILE, CHECKPOINT_FORMAT, CarriedMultipliers, Checkpoint, ExactF64s, RecordedFile,
    RunError,
};
use hagfish_scenario::ScenarioError;
use hagfish_sim::IntervalMaxima;
use proptest::prelude::*;

/// A checkpoint of realistic size (150 DOFs) with awkward values.
fn checkpoint() -> Checkpoint {
    let values: Vec<f64> = (0..150).map(|k| (k as f64 * 0.37).sin() / 3.0).collect();
    Checkpoint {
        format: CHECKPOINT_FORMAT,
        scenario_hash: "0123456789abcdef".into(),
        body_hash: "fedcba9876543210".into(),
        referenced_files_hash: Some("00112233aabbccdd".into()),
        frames: 42,
        steps: 420,
        t: ExactF64s(vec![4.2]),
        q: ExactF64s(values.clone()),
        qdot: ExactF64s(values.iter().map(|v| -2.0 * v).collect()),
        warm_start: CarriedMultipliers {
            rows: (0..20).map(|k| (3, k % 8)).collect(),
            values: ExactF64s(values[..60].to_vec()),
        },
        controller: ControllerState::default(),
        maxima: IntervalMaxima { self_penetration: 0.01, ..IntervalMaxima::default() },
        substepped_steps: 1,
        max_substeps: 2,
        resolved_steps: 1,
        files: vec![RecordedFile {
            name: "q.npy".into(),
            bytes: 128 + 8 * 150 * 42,
            fnv1a64: Some("0123456789abcdef".into()),
        }],
    }
}

/// The bytes of the written checkpoint, once per test binary.
fn written() -> &'static [u8] {
    static BYTES: std::sync::OnceLock<Vec<u8>> = std::sync::OnceLock::new();
    BYTES.get_or_init(|| {
        let dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR")).join("checkpoint_corruption");
        std::fs::create_dir_all(&dir).expect("a temporary directory");
        let path = dir.join(CHECKPOINT_FILE);
        checkpoint().write(&path).expect("written");
        assert_eq!(Checkpoint::read(&path).expect("read back"), checkpoint());
        std::fs::read(&path).expect("readable")
    })
}

#[derive(Clone, Debug)]
enum Damage {
    Flip { at: usize, bit: u8 },
    Truncate { keep: usize },
    Delete { at: usize, length: usize },
    Insert { at: usize, bytes: Vec<u8> },
}

fn damage() -> impl Strategy<Value = Damage> {
    prop_oneof![
        (any::<usize>(), 0u8..8).prop_map(|(at, bit)| Damage::Flip { at, bit }),
        any::<usize>().prop_map(|keep| Damage::Truncate { keep }),
        (any::<usize>(), 1usize..32).prop_map(|(at, length)| Damage::Delete { at, length }),
        (any::<usize>(), prop::collection::vec(any::<u8>(), 1..8))
            .prop_map(|(at, bytes)| Damage::Insert { at, bytes }),
    ]
}

/// Applies `damage` to `bytes`; an earlier truncation may have left nothing to flip, cut or
/// delete, and then only an insertion changes them.
fn apply(bytes: &mut Vec<u8>, damage: &Damage) {
    let len = bytes.len();
    if len == 0 && !matches!(damage, Damage::Insert { .. }) {
        return;
    }
    match damage {
        Damage::Flip { at, bit } => bytes[at % len] ^= 1 << bit,
        Damage::Truncate { keep } => bytes.truncate(keep % len),
        Damage::Delete { at, length } => {
            let start = at % len;
            bytes.drain(start..(start + length).min(len));
        }
        Damage::Insert { at, bytes: new } => {
            let start = at % (len + 1);
            bytes.splice(start..start, new.iter().copied());
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 512, ..ProptestConfig::default() })]

    #[test]
    fn a_damaged_checkpoint_is_refused(damages in prop::collection::vec(damage(), 1..3)) {
        let mut bytes = written().to_vec();
        for d in &damages {
            apply(&mut bytes, d);
        }
        prop_assume!(bytes != written());
        let dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR")).join("checkpoint_damaged");
        std::fs::create_dir_all(&dir).expect("a temporary directory");
        let path = dir.join(CHECKPOINT_FILE);
        std::fs::write(&path, &bytes).expect("write");
        match Checkpoint::read(&path) {
            Err(RunError::Checkpoint { path: named, .. }) => prop_assert_eq!(named, path),
            Err(RunError::Scenario(ScenarioError::DataFile(e))) => prop_assert!(e.to_string().contains(CHECKPOINT_FILE)),
            other => prop_assert!(false, "accepted or odd: {other:?}"),
        }
    }
}

/// A checkpoint of format 2 (positional multipliers, before decision 0036) is refused by its
/// format, with what to do, rather than by a parse error on its old field.
#[test]
fn a_checkpoint_of_format_2_is_refused_by_its_format() {
    let text = String::from_utf8(written().to_vec()).expect("ASCII");
    let (_, body) = text.split_once('\n').expect("a checksum line");
    let start = body.find("    warm_start:").expect("the warm start");
    let end = start + body[start..].find("\n    controller:").expect("the controller after it");
    let old = format!(
        "{}    multipliers: \"3fd5555555555555\",{}",
        &body[..start].replace("format: 3,", "format: 2,"),
        &body[end..]
    );
    let file = format!("// fnv1a64 {:016x}\n{old}", hagfish_sim::fnv1a64(old.as_bytes()));
    let dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR")).join("checkpoint_format_2");
    std::fs::create_dir_all(&dir).expect("a temporary directory");
    let path = dir.join(CHECKPOINT_FILE);
    std::fs::write(&path, file).expect("write");
    match Checkpoint::read(&path) {
        Err(RunError::Checkpoint { reason, .. }) => {
            assert!(reason.starts_with("format 2 (this build reads format 3"), "{reason}")
        }
        other => panic!("not refused by its format: {other:?}"),
    }
}
