fn main() {
    let v = sim::verilog::generate(sim::verilog::Top::Detector);
    std::fs::write("/tmp/vt/detector.v", &v).unwrap();
    let chk = sim::synth::yosys_latch_check(&v, "top").unwrap();
    println!("latches {} cells {}", chk.latches, chk.cells);
    let r = sim::synth::synthesize(&v, 125.0).unwrap();
    println!("{}", sim::synth::report_table(&r));
}
