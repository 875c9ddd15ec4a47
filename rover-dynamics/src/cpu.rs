//! Which instruction-set level the running processor offers, for the
//! generated plants' hot function.
//!
//! A generated plant compiles its right-hand side twice on x86-64: for the
//! baseline target the crate is built for, and for x86-64-v4 (AVX-512,
//! whose 32 vector registers spill far less of a straight-line function of
//! a thousand values than SSE2's 16). It picks one per call from
//! [`x86_64_v4`]. Rust never fuses a product and a sum on its own, so both
//! copies perform the same IEEE operations in the same order: the same
//! bits (a test holds them to it).
//!
//! With the `std` feature the answer comes from the processor at run time
//! (`is_x86_feature_detected!`, cached by std after the first call); in a
//! `no_std` build, from the target features the crate is compiled with.

/// The target features the generated plants' second copy is compiled with
/// (`#[target_feature(enable = …)]`, written by rover-codegen from this
/// constant): exactly the ones [`x86_64_v4`] checks.
pub const X86_64_V4_FEATURES: &str = "avx2,fma,avx512f,avx512vl";

/// Whether the processor running this code has every feature the
/// generated plants' second copy is compiled with: AVX2, FMA, AVX-512 F
/// and VL (the x86-64-v4 subset that straight-line floating-point code
/// uses), with the operating system saving their registers.
#[inline]
pub fn x86_64_v4() -> bool {
    #[cfg(all(feature = "std", target_arch = "x86_64"))]
    {
        std::is_x86_feature_detected!("avx2")
            && std::is_x86_feature_detected!("fma")
            && std::is_x86_feature_detected!("avx512f")
            && std::is_x86_feature_detected!("avx512vl")
    }
    #[cfg(not(all(feature = "std", target_arch = "x86_64")))]
    {
        cfg!(all(
            target_feature = "avx2",
            target_feature = "fma",
            target_feature = "avx512f",
            target_feature = "avx512vl"
        ))
    }
}
