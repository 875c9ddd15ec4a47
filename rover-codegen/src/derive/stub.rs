//! The companion type of an invalid description, next to its errors, with
//! every item of [`Item::ALL`], so that a bad description is its own error
//! only: code using `MyRover::plant()`, `MyRoverPlant::DOF`, the array and
//! nalgebra methods, the force path, the traits or `MyRover::report()`
//! still resolves (it never runs: the crate does not compile).
//!
//! The sizes are unknown, so the constants are empty arrays and the
//! methods are generic over the sizes of their arguments.

use proc_macro2::TokenStream;
use quote::{format_ident, quote};

use super::{Source, companion, described};
use crate::items::{Item, Kind};
use crate::plant_source::{ground_path, nalgebra_path, plant_path};

/// The stand-in plant `<Name>Plant` and what the derive adds for `<Name>`.
pub(super) fn stub(input: &syn::DeriveInput) -> TokenStream {
    let name = &input.ident;
    let plant = format_ident!("{}Plant", name);
    let vis = &input.vis;
    let stub = Stub {
        plant: &plant,
        rover: name.to_string(),
    };
    let mut out = quote! {
        #[derive(Clone, Copy, Debug, PartialEq)]
        #vis struct #plant;
    };
    for block in Item::blocks() {
        out.extend(match block {
            [item] if item.kind() == Kind::Impl => stub.item(*item),
            members => stub.inherent_impl(members),
        });
    }
    let source = Source {
        text: quote!(""),
        origin: quote!(""),
    };
    out.extend(companion(name, &plant));
    out.extend(described(name, &plant, &stub.rover, &source, "full", &[]));
    out
}

/// The stand-in plant type.
struct Stub<'a> {
    plant: &'a syn::Ident,
    /// Its `NAME`: the struct's name, as the description's is unknown.
    rover: String,
}

/// `::core::result::Result<(), PlantError>`, what the right-hand side returns.
fn rhs_result() -> TokenStream {
    let pl = plant_path();
    quote!(::core::result::Result<(), #pl::PlantError>)
}

/// A wheel state of zeros, the stand-in methods' kinematics.
fn zero_wheel() -> TokenStream {
    let pl = plant_path();
    quote! {
        #pl::WheelState { centre: [0.0; 3], velocity: [0.0; 3], spin_axis: [0.0; 3] }
    }
}

impl Stub<'_> {
    /// One inherent `impl` of `members`, each documented as a stub.
    fn inherent_impl(&self, members: &[Item]) -> TokenStream {
        let plant = self.plant;
        let members = members.iter().map(|item| self.item(*item));
        quote! {
            #[allow(clippy::all, unused_variables, dead_code)]
            impl #plant {
                #(
                    /// Stub.
                    #members
                )*
            }
        }
    }

    /// One item's stand-in: a trait impl whole, a constant or a method.
    fn item(&self, item: Item) -> TokenStream {
        match item {
            Item::Default => self.default_impl(),
            Item::Name => self.name_const(),
            Item::Dof => quote! { pub const DOF: usize = 0; },
            Item::Wheels => quote! { pub const WHEELS: usize = 0; },
            Item::Coordinates => quote! { pub const COORDINATES: [&'static str; 0] = []; },
            Item::WheelNames => quote! { pub const WHEEL_NAMES: [&'static str; 0] = []; },
            Item::SpringNeutrals => quote! { pub const SPRING_NEUTRALS: [f64; 0] = []; },
            Item::MinCosRoll => {
                quote! { pub const MIN_COS_ROLL: f64 = ::rover_dynamics::plant::MIN_COS_ROLL; }
            }
            Item::New => self.new_fn(),
            Item::CurrentNeutrals => quote! { pub fn spring_neutrals(&self) -> &[f64; 0] { &[] } },
            Item::DerivativesArray => rhs_array("derivatives_array"),
            Item::DerivativesPortable => rhs_array("derivatives_portable"),
            Item::MassMatrixArray => mass_matrix_array(),
            Item::WheelsArray => wheels_array(),
            Item::JacobianArray => jacobian_array(),
            Item::JacobianFixed => jacobian_fixed(),
            Item::Tyres => quote! { pub const TYRES: [::rover_dynamics::wheel_law::Tyre; 0] = []; },
            Item::Radii => quote! { pub const RADII: [f64; 0] = []; },
            Item::Ground => ground_fn(),
            Item::DerivativesOnGround => derivatives_on_ground(),
            Item::Plant => self.plant_impl(),
            Item::FixedPlant => self.fixed_plant_impl(),
        }
    }

    /// `NAME`: the struct's name.
    fn name_const(&self) -> TokenStream {
        let rover = &self.rover;
        quote!(pub const NAME: &'static str = #rover;)
    }

    /// `new`, a `const fn` as the real one.
    fn new_fn(&self) -> TokenStream {
        let plant = self.plant;
        quote!(pub const fn new() -> Self { #plant })
    }

    /// `Default`.
    fn default_impl(&self) -> TokenStream {
        let plant = self.plant;
        quote! {
            impl ::core::default::Default for #plant {
                fn default() -> Self { #plant }
            }
        }
    }

    /// `Plant`, for any lengths.
    fn plant_impl(&self) -> TokenStream {
        let (plant, result) = (self.plant, rhs_result());
        let pl = plant_path();
        quote! {
            impl #pl::Plant for #plant {
                fn dof(&self) -> usize { 0 }
                fn wheel_count(&self) -> usize { 0 }
                fn wheels(&mut self, _: &[f64], _: &[f64], _: &[f64], _: &mut [#pl::WheelState]) {}
                fn derivatives(
                    &mut self,
                    _: &[f64],
                    _: &[f64],
                    _: &[#pl::WheelLoad],
                    _: &mut [f64],
                    _: &mut [f64],
                ) -> #result {
                    Ok(())
                }
                fn mass_matrix(&mut self, _: &[f64], _: &mut [f64]) {}
                fn set_spring_neutral(&mut self, _: usize, _: f64) {}
            }
        }
    }

    /// `FixedPlant` for every size, and its methods as inherent ones too:
    /// a method call then takes its sizes from its arguments, where the
    /// trait's would need them all (`mass_matrix_fixed` has no wheels).
    fn fixed_plant_impl(&self) -> TokenStream {
        let (plant, result) = (self.plant, rhs_result());
        let (pl, na) = (plant_path(), nalgebra_path());
        let zero = zero_wheel();
        quote! {
            #[allow(clippy::all, unused_variables, dead_code)]
            impl #plant {
                /// Stub.
                pub fn derivatives_fixed<const N: usize, const W: usize>(
                    &self, x: &#na::SVector<f64, N>, w: &#na::SVector<f64, N>,
                    loads: &[#pl::WheelLoad; W], xdot: &mut #na::SVector<f64, N>,
                    wdot: &mut #na::SVector<f64, N>,
                ) -> #result { Ok(()) }
                /// Stub.
                pub fn mass_matrix_fixed<const N: usize>(
                    &self, x: &#na::SVector<f64, N>,
                ) -> #na::SMatrix<f64, N, N> {
                    #na::SMatrix::<f64, N, N>::from_array_storage(#na::ArrayStorage([[0.0; N]; N]))
                }
                /// Stub.
                pub fn wheels_fixed<const N: usize, const W: usize>(
                    &self, x: &#na::SVector<f64, N>, w: &#na::SVector<f64, N>,
                    steer: &#na::SVector<f64, W>,
                ) -> [#pl::WheelState; W] {
                    [#zero; W]
                }
            }
            #[allow(unused_variables)]
            impl<const N: usize, const W: usize> #pl::FixedPlant<N, W> for #plant {
                fn derivatives_fixed(
                    &self, x: &#na::SVector<f64, N>, w: &#na::SVector<f64, N>,
                    loads: &[#pl::WheelLoad; W], xdot: &mut #na::SVector<f64, N>,
                    wdot: &mut #na::SVector<f64, N>,
                ) -> #result { Ok(()) }
                fn mass_matrix_fixed(&self, x: &#na::SVector<f64, N>) -> #na::SMatrix<f64, N, N> {
                    #plant::mass_matrix_fixed(self, x)
                }
                fn wheels_fixed(
                    &self, x: &#na::SVector<f64, N>, w: &#na::SVector<f64, N>,
                    steer: &#na::SVector<f64, W>,
                ) -> [#pl::WheelState; W] {
                    #plant::wheels_fixed(self, x, w, steer)
                }
            }
        }
    }
}

/// `derivatives_array` or `derivatives_portable`, for any sizes.
fn rhs_array(name: &str) -> TokenStream {
    let (name, result, pl) = (format_ident!("{name}"), rhs_result(), plant_path());
    quote! {
        pub fn #name<const N: usize, const W: usize>(
            &self, x: &[f64; N], w: &[f64; N], loads: &[#pl::WheelLoad; W],
            xdot: &mut [f64; N], wdot: &mut [f64; N],
        ) -> #result { Ok(()) }
    }
}

/// `mass_matrix_array`, N × N zeros.
fn mass_matrix_array() -> TokenStream {
    quote! {
        pub fn mass_matrix_array<const N: usize>(&self, x: &[f64; N]) -> [[f64; N]; N] {
            [[0.0; N]; N]
        }
    }
}

/// `wheels_array`, one state of zeros per steering angle.
fn wheels_array() -> TokenStream {
    let (zero, pl) = (zero_wheel(), plant_path());
    quote! {
        pub fn wheels_array<const N: usize, const W: usize>(
            &self, x: &[f64; N], w: &[f64; N], steer: &[f64; W],
        ) -> [#pl::WheelState; W] {
            [#zero; W]
        }
    }
}

/// `jacobian_array`: its size 2N is not a const generic expression, so a
/// matrix that any index reads.
fn jacobian_array() -> TokenStream {
    let pl = plant_path();
    quote! {
        pub fn jacobian_array<const N: usize, const W: usize>(
            &self, x: &[f64; N], w: &[f64; N], loads: &[#pl::WheelLoad; W],
        ) -> ::rover_dynamics::described::StubMatrix {
            ::rover_dynamics::described::StubMatrix
        }
    }
}

/// `jacobian_fixed`, the same matrix that any index reads.
fn jacobian_fixed() -> TokenStream {
    let (pl, na) = (plant_path(), nalgebra_path());
    quote! {
        pub fn jacobian_fixed<const N: usize, const W: usize>(
            &self, x: &#na::SVector<f64, N>, w: &#na::SVector<f64, N>,
            loads: &[#pl::WheelLoad; W],
        ) -> ::rover_dynamics::described::StubMatrix {
            ::rover_dynamics::described::StubMatrix
        }
    }
}

/// `ground`, for any number of wheels.
fn ground_fn() -> TokenStream {
    let g = ground_path();
    quote! {
        pub fn ground<const W: usize>(search: #g::Search) -> #g::FixedGround<W> {
            #g::FixedGround::new(search)
        }
    }
}

/// `derivatives_on_ground`, for any sizes; the tyres' array is sized on its
/// own, as `TYRES` here is empty.
fn derivatives_on_ground() -> TokenStream {
    let g = ground_path();
    quote! {
        #[allow(clippy::too_many_arguments)]
        pub fn derivatives_on_ground<H, L, const N: usize, const W: usize, const T: usize>(
            &self,
            ground: &mut #g::FixedGround<W>,
            terrain: &H,
            law: &L,
            tyres: &[::rover_dynamics::wheel_law::Tyre; T],
            x: &[f64; N],
            w: &[f64; N],
            steer: &[f64; W],
            torques: impl FnOnce(&[f64; W]) -> [f64; W],
            xdot: &mut [f64; N],
            wdot: &mut [f64; N],
        ) -> ::core::result::Result<(), #g::GroundError>
        where
            H: ::rover_dynamics::HeightField + ?Sized,
            L: ::rover_dynamics::wheel_law::WheelLaw,
        {
            Ok(())
        }
    }
}
