fn main() {
    std::fs::write(std::env::args().nth(1).unwrap(), sim::verilog::generate(sim::verilog::Top::Detector)).unwrap();
}
