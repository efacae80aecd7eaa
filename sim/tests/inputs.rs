//! What a user's files can hold: `meta.txt` and images of any bytes are
//! read without a panic, and every refusal names the file.

use std::path::Path;

use image::{GrayImage, Luma};
use proptest::collection::vec;
use proptest::prelude::*;
use sim::eval::io::{load_grey, load_pair_dir};

/// A pair folder with small valid images and ground truth, and `meta` as
/// its `meta.txt`.
fn pair_folder(dir: &Path, meta: &[u8]) {
    let img = GrayImage::from_fn(24, 6, |x, y| Luma([(x * 9 + y * 5) as u8]));
    img.save(dir.join("left_gray.png")).unwrap();
    img.save(dir.join("right_gray.png")).unwrap();
    GrayImage::from_pixel(24, 6, Luma([32])).save(dir.join("disp_gt.png")).unwrap();
    std::fs::write(dir.join("meta.txt"), meta).unwrap();
}

/// A small valid PNG's bytes.
fn png_bytes() -> Vec<u8> {
    let mut out = std::io::Cursor::new(Vec::new());
    GrayImage::from_fn(16, 4, |x, y| Luma([(x * 13 + y * 7) as u8])).write_to(&mut out, image::ImageFormat::Png).unwrap();
    out.into_inner()
}

/// `bytes` written to a file `name` and read as an image: read, or refused
/// with an error that names the file (a panic fails the property).
fn read_as_image(bytes: &[u8], name: &str) -> Result<(), TestCaseError> {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join(name);
    std::fs::write(&path, bytes).unwrap();
    if let Err(e) = load_grey(&path) {
        prop_assert!(e.to_string().contains(&path.display().to_string()), "{e}");
    }
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 128, ..ProptestConfig::default() })]

    #[test]
    fn meta_txt_of_any_bytes_is_read_without_panic_and_a_refusal_names_the_file(bytes in vec(any::<u8>(), 0..300)) {
        let dir = tempfile::tempdir().unwrap();
        pair_folder(dir.path(), &bytes);
        if let Err(e) = load_pair_dir(dir.path()) {
            let msg = e.to_string();
            prop_assert!(msg.contains(&dir.path().display().to_string()), "{msg}");
        }
    }

    /// The `key: value` lines with numbers of either sign, in any order,
    /// with text after them: the pair loads with the number as written when
    /// it is positive, and is refused, naming `meta.txt`, when it is not.
    #[test]
    fn meta_txt_numbers_are_read_with_their_sign(
        dispmax in -200.0f64..200.0,
        scale in prop_oneof![Just(-16.0f64), Just(0.0), Just(1.0), Just(16.0), 0.5f64..300.0],
        tail in "[ a-z()=;]{0,12}",
        swap in any::<bool>(),
    ) {
        let lines = [format!("dispmax: {dispmax}{tail}"), format!("scale: {scale}{tail}")];
        let meta = if swap { format!("{}\n{}\n", lines[1], lines[0]) } else { format!("{}\n{}\n", lines[0], lines[1]) };
        let dir = tempfile::tempdir().unwrap();
        pair_folder(dir.path(), meta.as_bytes());
        // A `;` in the tail starts another scale: the first is the one read.
        match load_pair_dir(dir.path()) {
            Ok(p) => {
                prop_assert!(dispmax > 0.0 && scale > 0.0, "accepted {meta:?}");
                prop_assert_eq!(p.dispmax, dispmax);
                prop_assert!((p.gt_left[0] - 32.0 / scale).abs() < 1e-9, "ground truth 32 / {}: {}", scale, p.gt_left[0]);
            }
            Err(e) => {
                let msg = e.to_string();
                prop_assert!(dispmax <= 0.0 || scale <= 0.0, "refused {meta:?}: {msg}");
                prop_assert!(msg.contains("meta.txt") && msg.contains("must be positive"), "{msg}");
            }
        }
    }

    #[test]
    fn an_image_of_any_bytes_is_read_without_panic_and_a_refusal_names_the_file(bytes in vec(any::<u8>(), 0..300)) {
        read_as_image(&bytes, "left_gray.png")?;
    }

    /// A valid PNG with bytes changed (its header, chunk lengths, data):
    /// the decoder's paths past the signature.
    #[test]
    fn a_damaged_png_is_read_without_panic_and_a_refusal_names_the_file(
        changes in vec((any::<prop::sample::Index>(), any::<u8>()), 1..8),
        cut in any::<prop::sample::Index>(),
    ) {
        let mut bytes = png_bytes();
        for (at, v) in changes {
            let i = at.index(bytes.len());
            bytes[i] = v;
        }
        bytes.truncate(cut.index(bytes.len()) + 1);
        read_as_image(&bytes, "right_gray.png")?;
    }
}

/// The eight pairs' own `meta.txt` files: the numbers their lines start with.
#[test]
fn the_bundled_meta_txt_files_give_the_numbers_their_lines_start_with() {
    for (pair, dispmax) in [("tsukuba", 14.0), ("venus", 20.0), ("cones", 55.0), ("motorcycle", 60.0)] {
        let p = load_pair_dir(&sim::eval::io::stereo_data_dir().join(pair)).unwrap();
        assert_eq!(p.dispmax, dispmax, "{pair}");
    }
}
