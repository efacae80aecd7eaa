//! How the detector's input engine cuts one camera's AXI4-Stream video
//! beats into the lines it stores (`rtl::detector::declivity_detector`,
//! Overflow and Faults), for streams that break the rules as well as for
//! those that keep them:
//!
//! - a beat with `tuser` starts a line and a frame; inside a line it first
//!   ends that line (its width the pixels taken);
//! - a frame's first line stores at most `w_max` pixels; each later line of
//!   the frame at most the width the first one stored (the frame's width);
//! - a line ends on `tlast`, or on the last pixel it may store: it is then
//!   cut (`wide`), and the beats after it are dropped up to a `tlast` (also
//!   dropped) or a `tuser` (which starts the next line);
//! - lines before a stream's first `tuser` are limited by `w_max` alone;
//! - a line still open when the beats run out has not ended: it is not
//!   returned.
//!
//! A well-formed frame (`tuser` on the first pixel, `tlast` on each line's
//! last, lines of one width at most `w_max`) comes out as its rows.

/// One beat of a camera's stream: a grey level, start of frame, end of line.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct StreamBeat {
    pub pixel: u8,
    pub user: bool,
    pub last: bool,
}

/// One line as the detector stores it.
#[derive(Debug, Clone, PartialEq, Eq, Default)]
pub struct FramedLine {
    /// The pixels stored.
    pub pixels: Vec<u8>,
    /// The line starts a frame.
    pub sof: bool,
    /// The line was cut at its limit (its last stored pixel had no `tlast`).
    pub wide: bool,
}

/// The lines the detector stores from `beats` (module doc).
pub fn frame_lines(beats: &[StreamBeat], w_max: usize) -> Vec<FramedLine> {
    let mut lines = Vec::new();
    let mut frame_width = w_max;
    let mut line: Option<FramedLine> = None;
    let mut discard = false;
    for b in beats {
        if discard && !b.user {
            discard = !b.last;
            continue;
        }
        discard = false;
        if b.user {
            if let Some(open) = line.take() {
                if open.sof {
                    frame_width = open.pixels.len();
                }
                lines.push(open);
            }
        }
        let current = line.get_or_insert_with(|| FramedLine { sof: b.user, ..FramedLine::default() });
        let limit = if current.sof { w_max } else { frame_width };
        current.pixels.push(b.pixel);
        let at_limit = current.pixels.len() == limit;
        if b.last || at_limit {
            let mut done = line.take().unwrap_or_default();
            done.wide = !b.last;
            discard = !b.last;
            if done.sof {
                frame_width = done.pixels.len();
            }
            lines.push(done);
        }
    }
    lines
}

#[cfg(test)]
mod tests {
    use super::*;

    fn beats(lines: &[(usize, bool, bool)]) -> Vec<StreamBeat> {
        // (pixels, tuser on the first, tlast on the last); pixel values count.
        let mut v = Vec::new();
        for &(n, user, last) in lines {
            for x in 0..n {
                v.push(StreamBeat { pixel: (v.len() % 251) as u8, user: user && x == 0, last: last && x + 1 == n });
            }
        }
        v
    }

    fn shape(lines: &[FramedLine]) -> Vec<(usize, bool, bool)> {
        lines.iter().map(|l| (l.pixels.len(), l.sof, l.wide)).collect()
    }

    #[test]
    fn a_well_formed_frame_comes_out_as_its_rows() {
        let b = beats(&[(5, true, true), (5, false, true), (5, false, true)]);
        let got = frame_lines(&b, 16);
        assert_eq!(shape(&got), vec![(5, true, false), (5, false, false), (5, false, false)]);
        assert_eq!(got.iter().flat_map(|l| l.pixels.clone()).collect::<Vec<_>>(), b.iter().map(|b| b.pixel).collect::<Vec<_>>());
    }

    #[test]
    fn later_lines_are_cut_at_the_frames_width_and_their_rest_dropped_to_tlast() {
        // A longer second line: cut at 5, its 3 further beats dropped; a
        // shorter third line stored as it is.
        let got = frame_lines(&beats(&[(5, true, true), (8, false, true), (3, false, true)]), 16);
        assert_eq!(shape(&got), vec![(5, true, false), (5, false, true), (3, false, false)]);
    }

    #[test]
    fn a_missing_tlast_ends_the_line_at_the_frames_width_and_loses_the_next_line() {
        // Line 1 lacks tlast: it ends at 5 pixels, line 2 is dropped to its
        // tlast, line 3 comes through.
        let got = frame_lines(&beats(&[(5, true, true), (5, false, false), (5, false, true), (5, false, true)]), 16);
        assert_eq!(shape(&got), vec![(5, true, false), (5, false, true), (5, false, false)]);
    }

    #[test]
    fn a_first_line_without_tlast_runs_on_up_to_w_max_and_sets_that_width() {
        let got = frame_lines(&beats(&[(5, true, false), (5, false, true), (12, false, true)]), 8);
        assert_eq!(shape(&got), vec![(8, true, true), (8, false, true)]);
    }

    #[test]
    fn a_tuser_inside_a_line_ends_it_and_starts_a_frame() {
        // The second line is cut by a tuser after 3 pixels: a 3-pixel line,
        // then a new frame whose first line is 4 wide and limits the next.
        let got = frame_lines(&beats(&[(5, true, true), (3, false, false), (4, true, true), (6, false, true)]), 16);
        assert_eq!(shape(&got), vec![(5, true, false), (3, false, false), (4, true, false), (4, false, true)]);
    }

    #[test]
    fn a_line_left_open_at_the_end_is_not_returned() {
        let got = frame_lines(&beats(&[(5, true, true), (2, false, false)]), 16);
        assert_eq!(shape(&got), vec![(5, true, false)]);
    }
}
