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
//! The answer comes from the processor at run time, with or without `std`:
//! a crate that uses a generated plant with this crate's default features
//! off (firmware, or a user's benchmark with `default-features = false`)
//! gets the fast copy as a crate with the runtime does. With `std` it is
//! std's `is_x86_feature_detected!`; without, the same questions asked of
//! `cpuid` and `xgetbv` from `core::arch`, answered once and cached.

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
    #[cfg(all(not(feature = "std"), target_arch = "x86_64"))]
    {
        cfg!(all(
            target_feature = "avx2",
            target_feature = "fma",
            target_feature = "avx512f",
            target_feature = "avx512vl"
        )) || cached_cpuid_v4()
    }
    #[cfg(not(target_arch = "x86_64"))]
    {
        false
    }
}

/// [`cpuid_v4`], asked once: 0 not yet, 1 no, 2 yes.
#[cfg(target_arch = "x86_64")]
#[cfg_attr(feature = "std", allow(dead_code))]
#[inline]
fn cached_cpuid_v4() -> bool {
    use core::sync::atomic::{AtomicU8, Ordering};
    static ANSWER: AtomicU8 = AtomicU8::new(0);
    match ANSWER.load(Ordering::Relaxed) {
        0 => {
            let yes = cpuid_v4();
            ANSWER.store(if yes { 2 } else { 1 }, Ordering::Relaxed);
            yes
        }
        a => a == 2,
    }
}

/// The processor's answer, from `cpuid` and `xgetbv` (Intel SDM vol. 1,
/// §13.2 and §15.2): FMA and OSXSAVE in leaf 1, AVX2, AVX-512 F and VL in
/// leaf 7, and the operating system saving the SSE, AVX and AVX-512 state
/// (XCR0 bits 1–2 and 5–7).
#[cfg(target_arch = "x86_64")]
#[cfg_attr(feature = "std", allow(dead_code))]
pub(crate) fn cpuid_v4() -> bool {
    use core::arch::x86_64::{__cpuid, __cpuid_count};
    // `cpuid` is on every x86-64 processor.
    let max_leaf = __cpuid(0).eax;
    if max_leaf < 7 {
        return false;
    }
    let leaf1 = __cpuid(1);
    let leaf7 = __cpuid_count(7, 0);
    let fma = leaf1.ecx & (1 << 12) != 0;
    let osxsave = leaf1.ecx & (1 << 27) != 0;
    let avx2 = leaf7.ebx & (1 << 5) != 0;
    let avx512f = leaf7.ebx & (1 << 16) != 0;
    let avx512vl = leaf7.ebx & (1 << 31) != 0;
    if !(fma && osxsave && avx2 && avx512f && avx512vl) {
        return false;
    }
    // SAFETY: OSXSAVE is set, so `xgetbv` exists and the OS enabled it.
    let xcr0 = unsafe { xcr0() };
    const STATE: u64 = 0b1110_0110;
    xcr0 & STATE == STATE
}

/// XCR0, the state components the operating system saves.
///
/// # Safety
/// The processor must report OSXSAVE.
#[cfg(target_arch = "x86_64")]
#[cfg_attr(feature = "std", allow(dead_code))]
#[target_feature(enable = "xsave")]
unsafe fn xcr0() -> u64 {
    // SAFETY: compiled with `xsave`; the caller checked OSXSAVE.
    unsafe { core::arch::x86_64::_xgetbv(0) }
}

#[cfg(all(test, feature = "std", target_arch = "x86_64"))]
mod tests {
    #[test]
    fn cpuid_answers_as_std_does() {
        assert_eq!(super::cpuid_v4(), super::x86_64_v4());
    }
}
