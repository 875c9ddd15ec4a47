use rover_derive::Rover;

#[derive(Rover)]
#[rover(file = "../../../../rover-derive/tests/ui/unknown_field.toml")]
struct Typo;

include!("../uses/use_all.rs");

fn main() {
    use_all!(Typo, TypoPlant, 7, 2);
}
