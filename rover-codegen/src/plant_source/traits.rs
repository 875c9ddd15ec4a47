//! The plant type's trait impls, one function each: `Default`, and the two
//! interfaces of `rover_dynamics::plant` that the runtime and the user's
//! code drive a plant through.

use proc_macro2::TokenStream;
use quote::quote;

use super::{Plant, nalgebra_path, plant_path};

impl Plant {
    /// `Default`: `new()`, for code generic over plants that are `Default`.
    pub(super) fn default_impl(&self) -> TokenStream {
        let name = &self.name;
        quote! {
            impl ::core::default::Default for #name {
                fn default() -> Self {
                    Self::new()
                }
            }
        }
    }

    /// `Plant`, the slice interface the runtime drives every plant through:
    /// the array methods behind length checks.
    pub(super) fn plant_impl(&self) -> TokenStream {
        let (name, n, k, pl) = (&self.name, &self.n, &self.k, plant_path());
        let wheels = self.plant_wheels();
        let derivatives = self.plant_derivatives();
        let jacobian = self.plant_jacobian();
        quote! {
            /// Slices of the wrong length are not a panic: the outputs are filled with
            /// NaN (the runtime's finiteness check then stops the run). Missing
            /// steering angles and wheel loads count as zero, as in the generic plant.
            impl #pl::Plant for #name {
                fn dof(&self) -> usize {
                    #n
                }

                fn wheel_count(&self) -> usize {
                    #k
                }

                #wheels

                #derivatives

                fn mass_matrix(&mut self, x: &[f64], out: &mut [f64]) {
                    let Ok(x) = <&[f64; #n]>::try_from(x) else {
                        out.iter_mut().for_each(|v| *v = f64::NAN);
                        return;
                    };
                    let m = self.mass_matrix_array(x);
                    for (o, v) in out.iter_mut().zip(m.iter().flatten()) {
                        *o = *v;
                    }
                }

                fn set_spring_neutral(&mut self, coord: usize, neutral: f64) {
                    if let Some(n) = self.neutral.get_mut(coord) {
                        *n = neutral;
                    }
                }
                #jacobian
            }
        }
    }

    /// `Plant::wheels`: `wheels_array` on slices, the states written in
    /// place when there is one per wheel.
    fn plant_wheels(&self) -> TokenStream {
        let (n, k, pl) = (&self.n, &self.k, plant_path());
        quote! {
            fn wheels(&mut self, x: &[f64], w: &[f64], steer: &[f64], out: &mut [#pl::WheelState]) {
                let (Ok(x), Ok(w)) = (<&[f64; #n]>::try_from(x), <&[f64; #n]>::try_from(w)) else {
                    let nan = [f64::NAN; 3];
                    for o in out.iter_mut() {
                        *o = #pl::WheelState { centre: nan, velocity: nan, spin_axis: nan };
                    }
                    return;
                };
                let mut angles = [0.0; #k];
                for (a, s) in angles.iter_mut().zip(steer) {
                    *a = *s;
                }
                // The usual call, one state per wheel, gets the states written in
                // place instead of copied element by element (swing4: 765 → 729
                // instructions per call, callgrind).
                if let Ok(out) = <&mut [#pl::WheelState; #k]>::try_from(&mut *out) {
                    *out = self.wheels_array(x, w, &angles);
                    return;
                }
                for (o, s) in out.iter_mut().zip(self.wheels_array(x, w, &angles)) {
                    *o = s;
                }
            }
        }
    }

    /// `Plant::derivatives`: `derivatives_array` on slices, missing loads
    /// as zero.
    fn plant_derivatives(&self) -> TokenStream {
        let (n, k, pl) = (&self.n, &self.k, plant_path());
        quote! {
            fn derivatives(
                &mut self,
                x: &[f64],
                w: &[f64],
                loads: &[#pl::WheelLoad],
                xdot: &mut [f64],
                wdot: &mut [f64],
            ) -> ::core::result::Result<(), #pl::PlantError> {
                let (Ok(x), Ok(w), Ok(xdot), Ok(wdot)) = (
                    <&[f64; #n]>::try_from(x),
                    <&[f64; #n]>::try_from(w),
                    <&mut [f64; #n]>::try_from(&mut *xdot),
                    <&mut [f64; #n]>::try_from(&mut *wdot),
                ) else {
                    xdot.iter_mut().chain(wdot.iter_mut()).for_each(|v| *v = f64::NAN);
                    return Ok(());
                };
                if let Ok(loads) = <&[#pl::WheelLoad; #k]>::try_from(loads) {
                    return self.derivatives_array(x, w, loads, xdot, wdot);
                }
                let zero = #pl::WheelLoad { force: [0.0; 3], moment: [0.0; 3], stator_torque: [0.0; 3] };
                let mut fixed = [zero; #k];
                for (f, l) in fixed.iter_mut().zip(loads) {
                    *f = *l;
                }
                self.derivatives_array(x, w, &fixed, xdot, wdot)
            }
        }
    }

    /// `Plant::jacobian`, with the Jacobian only (the trait's default says
    /// there is none).
    fn plant_jacobian(&self) -> TokenStream {
        if self.bodies.jacobian.is_none() {
            return TokenStream::new();
        }
        let (n, k, pl) = (&self.n, &self.k, plant_path());
        quote! {
            fn jacobian(
                &mut self,
                x: &[f64],
                w: &[f64],
                loads: &[#pl::WheelLoad],
                jac: &mut [f64],
            ) -> ::core::option::Option<()> {
                let (Ok(x), Ok(w), Ok(loads)) = (
                    <&[f64; #n]>::try_from(x),
                    <&[f64; #n]>::try_from(w),
                    <&[#pl::WheelLoad; #k]>::try_from(loads),
                ) else {
                    return None;
                };
                for (o, v) in jac.iter_mut().zip(self.jacobian_array(x, w, loads).iter().flatten()) {
                    *o = *v;
                }
                Some(())
            }
        }
    }

    /// `FixedPlant`, the nalgebra interface: the array methods on the
    /// vectors' storage, without copies.
    pub(super) fn fixed_plant_impl(&self) -> TokenStream {
        let (name, n, k) = (&self.name, &self.n, &self.k);
        let (pl, na) = (plant_path(), nalgebra_path());
        quote! {
            /// The same plant on nalgebra's fixed-size types (no length checks, no heap).
            impl #pl::FixedPlant<#n, #k> for #name {
                #[inline]
                fn derivatives_fixed(
                    &self,
                    x: &#na::SVector<f64, #n>,
                    w: &#na::SVector<f64, #n>,
                    loads: &[#pl::WheelLoad; #k],
                    xdot: &mut #na::SVector<f64, #n>,
                    wdot: &mut #na::SVector<f64, #n>,
                ) -> ::core::result::Result<(), #pl::PlantError> {
                    self.derivatives_array(
                        &x.data.0[0],
                        &w.data.0[0],
                        loads,
                        &mut xdot.data.0[0],
                        &mut wdot.data.0[0],
                    )
                }

                #[inline]
                fn mass_matrix_fixed(&self, x: &#na::SVector<f64, #n>) -> #na::SMatrix<f64, #n, #n> {
                    // M is symmetric: its rows are its columns.
                    #na::SMatrix::from_array_storage(#na::ArrayStorage(self.mass_matrix_array(&x.data.0[0])))
                }

                #[inline]
                fn wheels_fixed(
                    &self,
                    x: &#na::SVector<f64, #n>,
                    w: &#na::SVector<f64, #n>,
                    steer: &#na::SVector<f64, #k>,
                ) -> [#pl::WheelState; #k] {
                    self.wheels_array(&x.data.0[0], &w.data.0[0], &steer.data.0[0])
                }
            }
        }
    }
}
