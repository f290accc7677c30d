//! Frames as an animation: animated GIF and APNG written here (the `image` and `png` crates),
//! MP4 (H.264) and WebM (VP9) through the system's ffmpeg (Debian's `ffmpeg` package), so that
//! browsers play them. Every file is written atomically.

use image::RgbaImage;
use std::io::Write;
use std::path::Path;
use std::process::{Command, Stdio};

use crate::BatchError;
use crate::files::{temp_beside, write_atomic};

/// The animation formats, by file extension.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Format {
    Gif,
    /// Animated PNG (`.png`, `.apng`): lossless, plays in every current browser.
    Apng,
    Mp4,
    Webm,
}

/// The format a path's extension names. Errors: any other extension.
pub fn format_of(path: &Path) -> Result<Format, BatchError> {
    let ext = path
        .extension()
        .map(|e| e.to_string_lossy().to_ascii_lowercase())
        .unwrap_or_default();
    Ok(match ext.as_str() {
        "gif" => Format::Gif,
        "png" | "apng" => Format::Apng,
        "mp4" => Format::Mp4,
        "webm" => Format::Webm,
        _ => {
            return Err(BatchError::Animation(format!(
                "{}: an animation is .mp4, .webm, .gif or .png/.apng (animated PNG)",
                path.display()
            )));
        }
    })
}

/// Writes `frames` (all one size) as an animation at `fps` frames per second, looping.
/// Errors: no frames, frames of different sizes, an encoder failure, no ffmpeg for MP4/WebM.
pub fn write(path: &Path, frames: &[RgbaImage], fps: f64) -> Result<(), BatchError> {
    let first = frames
        .first()
        .ok_or_else(|| BatchError::Animation("an animation needs at least one frame".into()))?;
    let (w, h) = first.dimensions();
    if let Some(i) = frames.iter().position(|f| f.dimensions() != (w, h)) {
        return Err(BatchError::Animation(format!(
            "frame {i} is {:?}, frame 0 is {w}×{h}",
            frames[i].dimensions()
        )));
    }
    if !(fps > 0.0 && fps <= 240.0) {
        return Err(BatchError::Animation(format!(
            "{fps} frames per second: give 0 < fps ≤ 240"
        )));
    }
    match format_of(path)? {
        Format::Gif => write_atomic(path, &gif(frames, fps).map_err(BatchError::Animation)?),
        Format::Apng => write_atomic(path, &apng(frames, fps).map_err(BatchError::Animation)?),
        format => ffmpeg(path, frames, fps, format).map_err(BatchError::Animation),
    }
}

fn gif(frames: &[RgbaImage], fps: f64) -> Result<Vec<u8>, String> {
    let mut bytes = Vec::new();
    {
        let mut encoder = image::codecs::gif::GifEncoder::new_with_speed(&mut bytes, 10);
        encoder
            .set_repeat(image::codecs::gif::Repeat::Infinite)
            .map_err(|e| e.to_string())?;
        // GIF delays are in hundredths of a second.
        let delay = image::Delay::from_numer_denom_ms((1000.0 / fps).round() as u32, 1);
        for f in frames {
            encoder
                .encode_frame(image::Frame::from_parts(f.clone(), 0, 0, delay))
                .map_err(|e| format!("GIF: {e}"))?;
        }
    }
    Ok(bytes)
}

fn apng(frames: &[RgbaImage], fps: f64) -> Result<Vec<u8>, String> {
    let (w, h) = frames[0].dimensions();
    let mut bytes = Vec::new();
    let err = |e: png::EncodingError| format!("APNG: {e}");
    {
        let mut encoder = png::Encoder::new(&mut bytes, w, h);
        encoder.set_color(png::ColorType::Rgba);
        encoder.set_depth(png::BitDepth::Eight);
        encoder.set_animated(frames.len() as u32, 0).map_err(err)?;
        // The delay as a fraction of a second: 1/fps, in thousandths where fps is fractional.
        let (num, den) = if fps.fract() == 0.0 {
            (1, fps as u16)
        } else {
            ((1000.0 / fps).round() as u16, 1000)
        };
        encoder.set_frame_delay(num, den).map_err(err)?;
        let mut writer = encoder.write_header().map_err(err)?;
        for f in frames {
            writer.write_image_data(f.as_raw()).map_err(err)?;
        }
        writer.finish().map_err(err)?;
    }
    Ok(bytes)
}

/// MP4 (H.264, yuv420p, +faststart) or WebM (VP9) by piping raw frames into ffmpeg. Odd sizes
/// are padded by one pixel (yuv420p needs even ones).
fn ffmpeg(path: &Path, frames: &[RgbaImage], fps: f64, format: Format) -> Result<(), String> {
    let (w, h) = frames[0].dimensions();
    let tmp = temp_beside(path);
    let (codec, extra): (&[&str], &[&str]) = match format {
        Format::Mp4 => (
            &["-c:v", "libx264", "-preset", "medium", "-crf", "18"],
            &["-movflags", "+faststart", "-f", "mp4"],
        ),
        _ => (
            &["-c:v", "libvpx-vp9", "-b:v", "0", "-crf", "30"],
            &["-f", "webm"],
        ),
    };
    if let Some(dir) = path.parent().filter(|p| !p.as_os_str().is_empty()) {
        std::fs::create_dir_all(dir)
            .map_err(|e| format!("cannot create {}: {e}", dir.display()))?;
    }
    let mut child = Command::new("ffmpeg")
        .args([
            "-hide_banner",
            "-loglevel",
            "error",
            "-y",
            "-f",
            "rawvideo",
            "-pix_fmt",
            "rgba",
        ])
        .args([
            "-s",
            &format!("{w}x{h}"),
            "-r",
            &format!("{fps}"),
            "-i",
            "-",
        ])
        .args([
            "-vf",
            "pad=ceil(iw/2)*2:ceil(ih/2)*2",
            "-pix_fmt",
            "yuv420p",
        ])
        .args(codec)
        .args(extra)
        .arg(&tmp)
        .stdin(Stdio::piped())
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .map_err(|e| {
            format!(
                "{}: MP4 and WebM are encoded by ffmpeg, which cannot be started ({e}); install \
                 it (Debian: apt install ffmpeg) or write .gif or .png (APNG)",
                path.display()
            )
        })?;
    let mut stdin = child.stdin.take().expect("piped");
    let fed = frames.iter().try_for_each(|f| stdin.write_all(f.as_raw()));
    drop(stdin);
    let output = child.wait_with_output().map_err(|e| e.to_string())?;
    if fed.is_err() || !output.status.success() {
        let _ = std::fs::remove_file(&tmp);
        let message = String::from_utf8_lossy(&output.stderr);
        return Err(format!(
            "{}: ffmpeg failed: {}",
            path.display(),
            message.lines().next().unwrap_or("no message")
        ));
    }
    std::fs::rename(&tmp, path).map_err(|e| format!("cannot write {}: {e}", path.display()))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn frames() -> Vec<RgbaImage> {
        (0..4u8)
            .map(|i| {
                RgbaImage::from_fn(9, 7, |x, y| {
                    image::Rgba([x as u8 * 20, y as u8 * 30, i * 60, 255])
                })
            })
            .collect()
    }

    #[test]
    fn apng_and_gif_decode_back_to_their_frames() {
        let dir = tempfile::tempdir().unwrap();
        let apng_path = dir.path().join("a.png");
        write(&apng_path, &frames(), 12.0).unwrap();
        let decoder = png::Decoder::new(std::io::BufReader::new(
            std::fs::File::open(&apng_path).unwrap(),
        ));
        let mut reader = decoder.read_info().unwrap();
        assert_eq!(reader.info().animation_control().unwrap().num_frames, 4);
        let mut buf = vec![0; reader.output_buffer_size().unwrap()];
        for f in frames() {
            reader.next_frame(&mut buf).unwrap();
            assert_eq!(&buf[..f.as_raw().len()], f.as_raw().as_slice(), "lossless");
        }
        let gif_path = dir.path().join("a.gif");
        write(&gif_path, &frames(), 10.0).unwrap();
        use image::AnimationDecoder;
        let decoded = image::codecs::gif::GifDecoder::new(std::io::BufReader::new(
            std::fs::File::open(&gif_path).unwrap(),
        ))
        .unwrap()
        .into_frames()
        .collect_frames()
        .unwrap();
        assert_eq!(decoded.len(), 4);
        assert_eq!(decoded[1].delay().numer_denom_ms(), (100, 1));
        assert!(
            write(&dir.path().join("a.avi"), &frames(), 10.0)
                .unwrap_err()
                .to_string()
                .contains(".mp4, .webm")
        );
        assert!(write(&gif_path, &[], 10.0).is_err());
    }
}
