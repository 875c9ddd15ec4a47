//! SplitMix64: the small, portable pseudo-random generator behind the random terrain.
//!
//! SplitMix64 (G. Steele, D. Lea, C. Flood, "Fast splittable pseudorandom
//! number generators", OOPSLA 2014; the constants are those of Java's
//! `SplittableRandom` and of S. Vigna's reference C code): a 64-bit counter
//! advanced by the golden-ratio increment and passed through a bijective
//! mixing function. It passes BigCrush, needs 8 bytes of state and only
//! wrapping integer arithmetic, so the same seed gives the same bits on
//! every machine and compiler.
//!
//! The random terrain uses it counter-style: the value of coarse node (i, j)
//! is `mix` of a key built from (seed, i, j), not the n-th draw of a stream,
//! so a node's value does not depend on the terrain's extent or on the order
//! in which nodes are visited — enlarging the map keeps the ground already there.

const GOLDEN_GAMMA: u64 = 0x9E37_79B9_7F4A_7C15;

/// The SplitMix64 output function: a bijection of 64-bit words with strong
/// avalanche (every input bit flips each output bit with probability ≈ 1/2).
#[inline]
pub fn mix(mut z: u64) -> u64 {
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^ (z >> 31)
}

/// A SplitMix64 stream.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct SplitMix64 {
    state: u64,
}

impl SplitMix64 {
    /// A stream starting from `seed` (any value, 0 included).
    pub fn new(seed: u64) -> SplitMix64 {
        SplitMix64 { state: seed }
    }

    /// The next 64 random bits.
    #[inline]
    pub fn next_u64(&mut self) -> u64 {
        self.state = self.state.wrapping_add(GOLDEN_GAMMA);
        mix(self.state)
    }

    /// The next value uniform in `[0, 1)`, a multiple of 2⁻⁵³.
    #[inline]
    pub fn next_f64(&mut self) -> f64 {
        unit_f64(self.next_u64())
    }
}

/// The top 53 bits of `bits` as a value in `[0, 1)` (exact conversion).
#[inline]
pub fn unit_f64(bits: u64) -> f64 {
    (bits >> 11) as f64 * (1.0 / (1u64 << 53) as f64)
}

/// 64 random bits for lattice node (`i`, `j`) under `seed`: the first output of
/// a SplitMix64 stream seeded with a key that mixes seed, i and j (each step
/// goes through `mix`, so nearby nodes and nearby seeds are uncorrelated).
#[inline]
pub fn lattice_bits(seed: u64, i: i64, j: i64) -> u64 {
    let key = mix(mix(seed.wrapping_add(GOLDEN_GAMMA)) ^ (i as u64));
    let key = mix(key.wrapping_add(GOLDEN_GAMMA) ^ (j as u64));
    SplitMix64::new(key).next_u64()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The first outputs for seed 1234567, from S. Vigna's reference
    /// `splitmix64.c` (as listed in many ports' test vectors).
    #[test]
    fn matches_the_reference_stream() {
        let mut g = SplitMix64::new(1_234_567);
        let expected = [
            6_457_827_717_110_365_317,
            3_203_168_211_198_807_973,
            9_817_491_932_198_370_423,
            4_593_380_528_125_082_431,
            16_408_922_859_458_223_821,
        ];
        for e in expected {
            assert_eq!(g.next_u64(), e);
        }
    }

    #[test]
    fn unit_values_stay_in_range() {
        assert_eq!(unit_f64(0), 0.0);
        assert!(unit_f64(u64::MAX) < 1.0);
    }
}
