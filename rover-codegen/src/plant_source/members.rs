//! The plant type's constants and methods, one function each; a method's
//! function writes the private functions only it calls after it.

use proc_macro2::{Ident, TokenStream};
use quote::{format_ident, quote};

use super::{Plant, ground_path, nalgebra_path, plant_path};

impl Plant {
    /// `NAME`: which description the plant is, without the description.
    pub(super) fn name_const(&self) -> TokenStream {
        let rover = &self.rover;
        quote! {
            /// The rover's name in its description.
            pub const NAME: &'static str = #rover;
        }
    }

    /// `DOF`: the length of `x` and `w` for callers that size arrays.
    pub(super) fn dof_const(&self) -> TokenStream {
        let n = &self.n;
        quote! {
            /// Number of generalized coordinates N = 6 + m.
            pub const DOF: usize = #n;
        }
    }

    /// `WHEELS`: the number of wheel states and loads.
    pub(super) fn wheels_const(&self) -> TokenStream {
        let k = &self.k;
        quote! {
            /// Number of wheels.
            pub const WHEELS: usize = #k;
        }
    }

    /// `COORDINATES`: what `x[6..]` holds, for output columns and messages.
    pub(super) fn coordinates_const(&self) -> TokenStream {
        let (m, names) = (&self.m, &self.coordinate_names);
        quote! {
            /// Names of the suspension coordinates y1 … ym.
            pub const COORDINATES: [&'static str; #m] = [#(#names),*];
        }
    }

    /// `WHEEL_NAMES`: which wheel each state and load is.
    pub(super) fn wheel_names_const(&self) -> TokenStream {
        let (k, names) = (&self.k, &self.wheel_names);
        quote! {
            /// Names of the wheels, in the description's order.
            pub const WHEEL_NAMES: [&'static str; #k] = [#(#names),*];
        }
    }

    /// `SPRING_NEUTRALS`: the state `new` starts from.
    pub(super) fn spring_neutrals_const(&self) -> TokenStream {
        let (m, neutrals) = (&self.m, &self.neutrals);
        quote! {
            /// The description's spring neutrals y_0.
            pub const SPRING_NEUTRALS: [f64; #m] = [#(#neutrals),*];
        }
    }

    /// `MIN_COS_ROLL`: the generic plant's bound, which the right-hand
    /// side checks, named where its error is read.
    pub(super) fn min_cos_roll_const(&self) -> TokenStream {
        let pl = plant_path();
        quote! {
            /// Smallest |cos φ| accepted before the attitude is singular (as the generic plant).
            pub const MIN_COS_ROLL: f64 = #pl::MIN_COS_ROLL;
        }
    }

    /// `new`: a `const fn`, so that a plant can be a `static`.
    pub(super) fn new_fn(&self) -> TokenStream {
        quote! {
            /// The plant with the description's spring neutrals.
            pub const fn new() -> Self {
                Self { neutral: Self::SPRING_NEUTRALS }
            }
        }
    }

    /// `spring_neutrals`: the state that `Plant::set_spring_neutral` moves.
    pub(super) fn spring_neutrals_fn(&self) -> TokenStream {
        let m = &self.m;
        quote! {
            /// The current spring neutrals y_0.
            pub fn spring_neutrals(&self) -> &[f64; #m] {
                &self.neutral
            }
        }
    }

    /// `fn <name>(&self, x, w, loads, xdot, wdot) -> Result<…>`: the
    /// signature of `derivatives_array` and of the copies behind it.
    fn rhs_signature(&self, name: &str) -> TokenStream {
        let (n, k, pl) = (&self.n, &self.k, plant_path());
        let name = format_ident!("{name}");
        quote! {
            fn #name(&self, x: &[f64; #n], w: &[f64; #n], loads: &[#pl::WheelLoad; #k],
                xdot: &mut [f64; #n], wdot: &mut [f64; #n])
                -> ::core::result::Result<(), #pl::PlantError>
        }
    }

    /// `derivatives_array`, which picks the copy of the right-hand side the
    /// processor runs fastest, and the x86-64-v4 copy.
    pub(super) fn derivatives_array(&self) -> TokenStream {
        let signature = self.rhs_signature("derivatives_array");
        let v4 = self.derivatives_v4();
        quote! {
            /// `ẋ = B·w` and `ẇ = M⁻¹·(−Ṁ·w − f1 + f2 + Q)` (MODEL.md §5) on
            /// plain arrays ([`::rover_dynamics::plant::FixedPlant::derivatives_fixed`] is the
            /// same on nalgebra vectors). The outputs are written in any case; the error says
            /// the attitude is singular (|cos φ| < 1e-6) or M is not positive
            /// definite (an LDLᵀ pivot not > 0), as the generic plant does; the
            /// suspension rows are eliminated first, so a failing pivot is checked
            /// in that order and reported with its row of M.
            ///
            /// On x86-64 the body is compiled twice, for the crate's target and for
            /// x86-64-v4, and each call takes the second when the processor has it
            /// ([`::rover_dynamics::cpu`]): the same operations, the same bits.
            #[inline]
            pub #signature {
                #[cfg(target_arch = "x86_64")]
                if ::rover_dynamics::cpu::x86_64_v4() {
                    // SAFETY: the processor has the features `derivatives_v4` is
                    // compiled for.
                    return unsafe { self.derivatives_v4(x, w, loads, xdot, wdot) };
                }
                self.derivatives_portable(x, w, loads, xdot, wdot)
            }
            #v4
        }
    }

    /// `derivatives_v4`: the right-hand side compiled for the features the
    /// dispatch checks.
    fn derivatives_v4(&self) -> TokenStream {
        let signature = self.rhs_signature("derivatives_v4");
        let (body, features) = (&self.bodies.rhs.v4, rover_dynamics::cpu::X86_64_V4_FEATURES);
        quote! {
            /// [`Self::derivatives_array`] compiled for x86-64-v4 (AVX-512: 32
            /// vector registers, so the straight-line body spills less); called
            /// only when [`::rover_dynamics::cpu::x86_64_v4`] finds those features.
            #[cfg(target_arch = "x86_64")]
            #[target_feature(enable = #features)]
            #signature {
                #body
            }
        }
    }

    /// `derivatives_portable`, public for the tests that hold the two
    /// copies to the same bits, then the body both copies inline (without
    /// lanes) and the out-of-line error of a singular M.
    pub(super) fn derivatives_portable(&self) -> TokenStream {
        let signature = self.rhs_signature("derivatives_portable");
        let body = &self.bodies.rhs.portable;
        let shared = self.derivatives_body();
        let singular_mass = self.singular_mass();
        quote! {
            /// [`Self::derivatives_array`] for the crate's own target only,
            /// whatever the processor offers (the reference of the tests that hold
            /// the two copies to the same bits). Out of line, as the one function
            /// its callers share: inlined, the body would be copied into each.
            #[doc(hidden)]
            #[inline(never)]
            pub #signature {
                #body
            }
            #shared
            #singular_mass
        }
    }

    /// `derivatives_body`, the scalar right-hand side, when the copies
    /// share one.
    fn derivatives_body(&self) -> TokenStream {
        let Some(body) = &self.bodies.rhs.shared else {
            return TokenStream::new();
        };
        let signature = self.rhs_signature("derivatives_body");
        quote! {
            /// The body of both copies, inlined into each so that each is compiled
            /// for its own instruction set.
            #[inline(always)]
            #signature {
                #body
            }
        }
    }

    /// `singular_mass`: the error of a pivot that is not > 0, kept off the
    /// path that succeeds.
    fn singular_mass(&self) -> TokenStream {
        let (n, pl) = (&self.n, plant_path());
        quote! {
            /// The first pivot (row, numerator, denominator) whose numerator is not
            /// > 0, as the error; out of line, so that the pivots are not stored
            /// on the way to `Ok` (M is positive definite on every sane state).
            #[cold]
            #[inline(never)]
            fn singular_mass(
                pivots: [(usize, f64, f64); #n],
            ) -> ::core::result::Result<(), #pl::PlantError> {
                for (row, num, den) in pivots {
                    if num.is_nan() || num <= 0.0 {
                        return Err(#pl::PlantError::SingularMass { row, pivot: num / den });
                    }
                }
                Ok(())
            }
        }
    }

    /// `mass_matrix_array`: M's rows, zeros where M has structural zeros.
    pub(super) fn mass_matrix_array(&self) -> TokenStream {
        let (n, body) = (&self.n, &self.bodies.mass);
        quote! {
            /// The mass matrix M(y) (MODEL.md §4) as rows; structural zeros are
            /// not computed.
            #[inline]
            pub fn mass_matrix_array(&self, x: &[f64; #n]) -> [[f64; #n]; #n] {
                let mut m = [[0.0; #n]; #n];
                #body
                m
            }
        }
    }

    /// `wheels_array`: each wheel's centre, velocity and spin axis.
    pub(super) fn wheels_array(&self) -> TokenStream {
        let (n, k, pl, body) = (&self.n, &self.k, plant_path(), &self.bodies.wheels);
        let steer: &Ident = &self.steer;
        quote! {
            /// Wheel-centre kinematics for the steering angles `steer` (ignored for
            /// wheels that are not steerable), MODEL.md §3, on plain arrays.
            #[inline]
            pub fn wheels_array(
                &self,
                x: &[f64; #n],
                w: &[f64; #n],
                #steer: &[f64; #k],
            ) -> [#pl::WheelState; #k] {
                let mut out = [#pl::WheelState { centre: [0.0; 3], velocity: [0.0; 3], spin_axis: [0.0; 3] }; #k];
                #body
                out
            }
        }
    }

    /// `jacobian_array`, with the Jacobian only: the derivatives of the
    /// right-hand side, for implicit integrators.
    pub(super) fn jacobian_array(&self) -> TokenStream {
        let Some(body) = &self.bodies.jacobian else {
            return TokenStream::new();
        };
        let (n, k, two_n, pl) = (&self.n, &self.k, &self.two_n, plant_path());
        quote! {
            /// The exact Jacobian `∂(ẋ, ẇ)/∂(x, w)` at fixed wheel loads,
            /// `jac[i][j] = ∂f_i/∂s_j` with `f = [ẋ; ẇ]`, `s = [x; w]`
            /// (symbolic differentiation of the traced equations), as rows.
            #[inline]
            pub fn jacobian_array(
                &self,
                x: &[f64; #n],
                w: &[f64; #n],
                loads: &[#pl::WheelLoad; #k],
            ) -> [[f64; #two_n]; #two_n] {
                let mut jac = [[0.0; #two_n]; #two_n];
                #body
                jac
            }
        }
    }

    /// `jacobian_fixed`, with the Jacobian only: `jacobian_array` on
    /// nalgebra's types.
    pub(super) fn jacobian_fixed(&self) -> TokenStream {
        if self.bodies.jacobian.is_none() {
            return TokenStream::new();
        }
        let (n, k, two_n) = (&self.n, &self.k, &self.two_n);
        let (pl, na) = (plant_path(), nalgebra_path());
        quote! {
            /// The exact Jacobian `∂(ẋ, ẇ)/∂(x, w)` at fixed wheel loads as a
            /// nalgebra matrix, `jac[(i, j)] = ∂f_i/∂s_j`.
            #[inline]
            pub fn jacobian_fixed(
                &self,
                x: &#na::SVector<f64, #n>,
                w: &#na::SVector<f64, #n>,
                loads: &[#pl::WheelLoad; #k],
            ) -> #na::SMatrix<f64, #two_n, #two_n> {
                let rows = self.jacobian_array(&x.data.0[0], &w.data.0[0], loads);
                // nalgebra stores columns: the rows read as columns are the transpose.
                #na::SMatrix::from_array_storage(#na::ArrayStorage(rows)).transpose()
            }
        }
    }

    /// `TYRES`: the wheel law's constants, which the force path takes as an
    /// argument so that a caller can change them (rolling resistance).
    pub(super) fn tyres_const(&self) -> TokenStream {
        let (k, tyres) = (&self.k, &self.tyres);
        quote! {
            /// Each wheel's tyre, in the description's order: stiffness k_w,
            /// damping c_w, friction limits, cornering stiffness; no rolling
            /// resistance (a copy with `rolling_resistance` set adds it).
            pub const TYRES: [::rover_dynamics::wheel_law::Tyre; #k] = [#(#tyres),*];
        }
    }

    /// `RADII`: the contact search's wheel radii.
    pub(super) fn radii_const(&self) -> TokenStream {
        let (k, radii) = (&self.k, &self.radii);
        quote! {
            /// Each wheel's radius R_w \[m\], in the description's order.
            pub const RADII: [f64; #k] = [#(#radii),*];
        }
    }

    /// `ground`: the force path's state, sized for this rover's wheels.
    pub(super) fn ground_fn(&self) -> TokenStream {
        let (k, g) = (&self.k, ground_path());
        quote! {
            /// The ground under this rover's wheels, searched by `search`, for
            /// [`Self::derivatives_on_ground`]; it keeps what each wheel's search
            /// proved between calls (a few kilobytes per wheel, no heap).
            pub fn ground(search: #g::Search) -> #g::FixedGround<#k> {
                #g::FixedGround::new(search)
            }
        }
    }

    /// `derivatives_on_ground`: the whole right-hand side on a height
    /// field, with the contact search and the wheel law of
    /// `rover_dynamics::wheel_ground` (the generic plant's very code) and
    /// this rover's constants.
    pub(super) fn derivatives_on_ground(&self) -> TokenStream {
        let (n, k, g) = (&self.n, &self.k, ground_path());
        quote! {
            /// The whole right-hand side on the ground `terrain`, as the runtime
            /// computes it with the generic plant: the wheels' kinematics for the
            /// steering angles `steer`, each wheel's contact, the motor torques
            /// `torques(normals)` [N·m] chosen from the wheels' normal forces \[N\]
            /// (a controller that shares torque by load reads them; an open-loop
            /// rig ignores them), the wheel law `law` on every patch with the
            /// tyres `tyres` (`&Self::TYRES`, a constant the compiler folds in),
            /// their reduction to loads, and `ẋ`, `ẇ`. The contact search and the
            /// law are `rover_dynamics::wheel_ground`'s, the code the generic
            /// plant's runs use; what each wheel did is in `ground.reports()`.
            #[inline]
            #[allow(clippy::too_many_arguments)]
            pub fn derivatives_on_ground<H, L>(
                &self,
                ground: &mut #g::FixedGround<#k>,
                terrain: &H,
                law: &L,
                tyres: &[::rover_dynamics::wheel_law::Tyre; #k],
                x: &[f64; #n],
                w: &[f64; #n],
                steer: &[f64; #k],
                torques: impl FnOnce(&[f64; #k]) -> [f64; #k],
                xdot: &mut [f64; #n],
                wdot: &mut [f64; #n],
            ) -> ::core::result::Result<(), #g::GroundError>
            where
                H: ::rover_dynamics::HeightField + ?Sized,
                L: ::rover_dynamics::wheel_law::WheelLaw,
            {
                let states = self.wheels_array(x, w, steer);
                let normals = ground
                    .find_contacts(terrain, &states, tyres, &Self::RADII)
                    .map_err(#g::GroundError::OffMap)?;
                let torques = torques(normals);
                let loads = *ground.loads(law, &states, tyres, &torques);
                self.derivatives_array(x, w, &loads, xdot, wdot)
                    .map_err(#g::GroundError::Plant)
            }
        }
    }
}
