//! The C library's step allocates nothing: 2,000 steps of 1 ms of the
//! shipped rough-ground scenario (swing4, its height map, its speed loop,
//! RK4) with torques set before each, after one warm-up step. Its own
//! test binary: it installs a counting global allocator.

use std::ffi::{CString, c_char, c_int, c_void};

use rover_plant as _;

unsafe extern "C" {
    fn rover_create(
        scenario: *const c_char,
        out: *mut *mut c_void,
        m: *mut c_char,
        n: usize,
    ) -> c_int;
    fn rover_step(p: *mut c_void, dt: f64) -> c_int;
    fn rover_set_torques(p: *mut c_void, v: *const f64, n: usize) -> c_int;
    fn rover_outputs(p: *mut c_void, out: *mut f64, n: usize) -> c_int;
    fn rover_destroy(p: *mut c_void);
}

#[test]
fn two_thousand_steps_of_the_c_library_allocate_nothing() {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../scenarios/export_rough.toml"
    );
    let path = CString::new(path).unwrap();
    let mut p = std::ptr::null_mut();
    let mut message = [0 as c_char; 512];
    assert_eq!(
        unsafe { rover_create(path.as_ptr(), &mut p, message.as_mut_ptr(), 512) },
        0
    );
    let mut out = vec![0.0; 70];
    assert_eq!(unsafe { rover_step(p, 1e-3) }, 0);
    let probe = allocation_counter::measure(|| {
        std::hint::black_box(vec![1u8; 8]);
    });
    assert_eq!(probe.count_total, 1, "the counter counts");
    let counts = allocation_counter::measure(|| {
        for k in 0..2000 {
            let tau = 0.01 * (k % 7) as f64;
            let torques = [tau, tau, tau, tau];
            assert_eq!(unsafe { rover_set_torques(p, torques.as_ptr(), 4) }, 0);
            assert_eq!(unsafe { rover_step(p, 1e-3) }, 0);
            assert_eq!(unsafe { rover_outputs(p, out.as_mut_ptr(), out.len()) }, 0);
        }
    });
    assert_eq!(
        counts.count_total, 0,
        "{} allocations in 2000 steps",
        counts.count_total
    );
    assert!(out[1] > 0.0, "the rover drove: X = {}", out[1]);
    unsafe { rover_destroy(p) };
}
