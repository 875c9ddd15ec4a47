use rover_derive::Rover;

#[derive(Rover)]
struct NoDescription;

include!("../uses/use_all.rs");

fn main() {
    use_all!(NoDescription, NoDescriptionPlant, 7, 2);
}
