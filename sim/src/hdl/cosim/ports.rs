//! The ports of a Verilog design's top module, parsed from its text.

use super::error::*;
use super::trace::*;

/// The ports of the design's `top` module, parsed from its Verilog (both
/// rust-hdl's non-ANSI style and ANSI headers). The clock is included.
pub fn top_ports(design: &str) -> Result<(Vec<Port>, Vec<Port>), CosimError> {
    let toks = tokenize(design);
    let start = toks
        .windows(2)
        .position(|w| w[0] == "module" && w[1] == TOP_MODULE)
        .ok_or_else(|| {
            CosimError::PortsDiffer(format!("no `module {TOP_MODULE}` in the design"))
        })?;
    let mut ins = Vec::new();
    let mut outs = Vec::new();
    let mut dir: Option<bool> = None; // Some(true) input, Some(false) output
    let mut width = 1u32;
    let mut i = start + 2;
    while i < toks.len() {
        let t = toks[i].as_str();
        match t {
            "endmodule" => break,
            "input" | "output" => {
                dir = Some(t == "input");
                width = 1;
            }
            "inout" => {
                return Err(CosimError::PortsDiffer(
                    "`inout` ports are not supported".into(),
                ))
            }
            ";" | ")" => dir = None,
            "wire" | "reg" | "logic" | "signed" | "unsigned" | "," | "(" => {}
            _ if t.starts_with('[') => {
                if dir.is_some() {
                    width = range_width(t).ok_or_else(|| {
                        CosimError::PortsDiffer(format!("cannot read the range `{t}`"))
                    })?;
                }
            }
            _ => {
                if let Some(is_in) = dir {
                    let p = Port {
                        name: t.to_string(),
                        width,
                    };
                    if is_in {
                        ins.push(p);
                    } else {
                        outs.push(p);
                    }
                }
            }
        }
        i += 1;
    }
    Ok((ins, outs))
}

fn tokenize(s: &str) -> Vec<String> {
    let mut toks = Vec::new();
    let mut cur = String::new();
    let mut chars = s.chars().peekable();
    let push = |toks: &mut Vec<String>, cur: &mut String| {
        if !cur.is_empty() {
            toks.push(std::mem::take(cur));
        }
    };
    while let Some(c) = chars.next() {
        match c {
            '/' if chars.peek() == Some(&'/') => {
                push(&mut toks, &mut cur);
                for c in chars.by_ref() {
                    if c == '\n' {
                        break;
                    }
                }
            }
            '/' if chars.peek() == Some(&'*') => {
                push(&mut toks, &mut cur);
                chars.next();
                let mut prev = ' ';
                for c in chars.by_ref() {
                    if prev == '*' && c == '/' {
                        break;
                    }
                    prev = c;
                }
            }
            '[' => {
                push(&mut toks, &mut cur);
                let mut r = String::from("[");
                for c in chars.by_ref() {
                    if !c.is_whitespace() {
                        r.push(c);
                    }
                    if c == ']' {
                        break;
                    }
                }
                toks.push(r);
            }
            '(' | ')' | ',' | ';' => {
                push(&mut toks, &mut cur);
                toks.push(c.to_string());
            }
            c if c.is_whitespace() => push(&mut toks, &mut cur),
            c => cur.push(c),
        }
    }
    push(&mut toks, &mut cur);
    toks
}

fn range_width(r: &str) -> Option<u32> {
    let inner = r.strip_prefix('[')?.strip_suffix(']')?;
    let (a, b) = inner.split_once(':')?;
    let a: i64 = a.parse().ok()?;
    let b: i64 = b.parse().ok()?;
    u32::try_from((a - b).abs() + 1).ok()
}

/// Checks that the design's `top` has the clock input and exactly the
/// trace's ports (by name and width; order does not matter).
pub(crate) fn check_design_ports(design: &str, trace: &Trace) -> Result<(), CosimError> {
    let (ins, outs) = top_ports(design)?;
    let mut problems = Vec::new();
    match ins.iter().find(|p| p.name == CLOCK_PORT) {
        Some(p) if p.width == 1 => {}
        Some(p) => problems.push(format!("`{CLOCK_PORT}` is {} bits wide", p.width)),
        None => problems.push(format!("no `{CLOCK_PORT}` input")),
    }
    let ins: Vec<Port> = ins.into_iter().filter(|p| p.name != CLOCK_PORT).collect();
    for (kind, design_ports, trace_ports) in [
        ("input", &ins, &trace.inputs),
        ("output", &outs, &trace.outputs),
    ] {
        for p in design_ports.iter() {
            match trace_ports.iter().find(|q| q.name == p.name) {
                None => problems.push(format!("design {kind} `{p}` is not in the trace")),
                Some(q) if q.width != p.width => problems.push(format!(
                    "{kind} `{}` is {} bits in the design, {} in the trace",
                    p.name, p.width, q.width
                )),
                Some(_) => {}
            }
        }
        for q in trace_ports.iter() {
            if !design_ports.iter().any(|p| p.name == q.name) {
                problems.push(format!("trace {kind} `{q}` is not a design {kind}"));
            }
        }
    }
    if problems.is_empty() {
        Ok(())
    } else {
        Err(CosimError::PortsDiffer(problems.join("; ")))
    }
}
