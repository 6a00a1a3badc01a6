//! FNV-1a (64 bit) fingerprints: of a resolved scenario's text and of a state's bits, printed
//! as 16 hexadecimal digits. Not cryptographic; they tell runs and states apart.

use hagfish_tree::State;

const OFFSET: u64 = 0xcbf2_9ce4_8422_2325;
const PRIME: u64 = 0x0000_0100_0000_01b3;

/// The FNV-1a hash of `bytes`.
pub fn fnv1a64(bytes: &[u8]) -> u64 {
    bytes.iter().fold(OFFSET, |hash, &b| (hash ^ u64::from(b)).wrapping_mul(PRIME))
}

/// The hash of the bits of t, then every q, then every q̇ (little-endian), as 16 hex digits:
/// equal exactly when the states are bit-identical (up to hash collisions).
pub fn state_hash(state: &State) -> String {
    let values = std::iter::once(&state.t).chain(&state.q).chain(&state.qdot);
    let bytes: Vec<u8> = values.flat_map(|v| v.to_bits().to_le_bytes()).collect();
    format!("{:016x}", fnv1a64(&bytes))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn known_values_and_sensitivity_to_one_bit() {
        assert_eq!(fnv1a64(b""), OFFSET);
        assert_eq!(fnv1a64(b"a"), 0xaf63_dc4c_8601_ec8c);
        let state = State { t: 1.0, q: vec![0.5, -0.25], qdot: vec![0.0, 2.0] };
        let mut other = state.clone();
        other.qdot[0] = -0.0;
        assert_ne!(state_hash(&state), state_hash(&other));
        assert_eq!(state_hash(&state), state_hash(&state.clone()));
    }
}
