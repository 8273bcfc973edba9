//! Importing one frame: the calls read from the capture's start (state is
//! tracked through every earlier frame), the selected frame's draws
//! recorded, then placed in the frame (its size is the viewports' extent)
//! as a clip-space [`Scene`] of one mesh and one material per draw, in
//! issue order.

use super::args::CallError;
use super::draw::{self, DrawRec};
use super::scene::{self, TextureInfo};
use super::tracker::{Context, Effect};
use crate::Scene;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use wasp_gltrace::{Call, CaptureError};

/// What to import.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct ImportOptions {
    /// The frame (from 0); `None`: the last complete one.
    pub frame: Option<u64>,
    /// Count draws that need what is not modelled instead of failing.
    pub skip_unsupported: bool,
}

/// An error importing: the capture's own, or one at a call or a frame,
/// with the file.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum ImportError {
    /// Reading the capture failed.
    Capture(CaptureError),
    /// A call the importer refuses.
    Call(PathBuf, CallError),
    /// The frame asked for is not there, or has no size.
    Frame(PathBuf, String),
}

impl std::fmt::Display for ImportError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            ImportError::Capture(e) => write!(f, "{e}"),
            ImportError::Call(p, e) => write!(f, "{}, {e}", p.display()),
            ImportError::Frame(p, m) => write!(f, "{}: {m}", p.display()),
        }
    }
}

impl std::error::Error for ImportError {}

impl From<CaptureError> for ImportError {
    fn from(e: CaptureError) -> Self {
        ImportError::Capture(e)
    }
}

/// One frame imported: the scene to rasterize and what the import saw.
#[derive(Clone, Debug)]
pub struct Imported {
    pub scene: Scene,
    pub width: u32,
    pub height: u32,
    /// The frame's index and its calls (first, last: the swap).
    pub frame: u64,
    pub calls: (u64, u64),
    /// Complete frames read (all of the capture's when the last was
    /// asked for).
    pub frames_read: u64,
    pub draw_calls: u64,
    /// The draws' call numbers, in issue order (material `i` is draw `i`).
    pub draw_call_numbers: Vec<u64>,
    pub triangles: u64,
    /// Draws skipped (with `skip_unsupported`), by what they need.
    pub unsupported: BTreeMap<String, u64>,
    /// Unsupported draws of the frames before it (not imported), by
    /// feature.
    pub unsupported_in_earlier_frames: BTreeMap<String, u64>,
    /// Calls up to the frame's end the model does not use, by name.
    pub unmodelled: BTreeMap<String, u64>,
    pub textures: Vec<TextureInfo>,
    /// The GL name of each of the scene's textures (a 3D texture's slices
    /// share theirs).
    pub texture_ids: Vec<u32>,
    /// The draw (index in issue order) of each of the scene's materials:
    /// material `i` is draw `i` for the draws, and the materials after
    /// them are of the draws that read several choices of 3D slices
    /// ([`super::scene`]).
    pub material_draws: Vec<usize>,
}

/// A frame read to its swap: its recording, the unmodelled calls and the
/// earlier frames' unsupported draws up to it, and its swap's number.
struct Finished {
    index: u64,
    build: FrameBuild,
    unmodelled: BTreeMap<String, u64>,
    earlier: BTreeMap<String, u64>,
    last_call: u64,
}

/// One frame's recording.
#[derive(Default)]
struct FrameBuild {
    first_call: u64,
    draws: Vec<DrawRec>,
    unsupported: BTreeMap<String, u64>,
    /// Of those, the draws the tracker refused without recording
    /// (immediate mode, display lists...).
    refused: BTreeMap<String, u64>,
    first_unsupported: Option<CallError>,
    error: Option<CallError>,
}

impl FrameBuild {
    /// A draw that needs `feature`; `refused` by the tracker (else found
    /// out recording it).
    fn unsupported(&mut self, call: &Call, feature: String, refused: bool) {
        self.first_unsupported.get_or_insert_with(|| {
            CallError::at(call, format!("needs {feature}, which is not modelled"))
        });
        if refused {
            *self.refused.entry(feature.clone()).or_default() += 1;
        }
        *self.unsupported.entry(feature).or_default() += 1;
    }
}

/// Import one frame of the calls `calls` (read from `file`).
pub fn import(
    calls: impl IntoIterator<Item = Result<Call, CaptureError>>,
    file: &Path,
    opts: ImportOptions,
) -> Result<Imported, ImportError> {
    let mut reader = Reader::new(calls, file, opts.skip_unsupported);
    if let Some(n) = opts.frame {
        return reader.frame(n);
    }
    // The last complete frame: every frame recorded (its unsupported
    // draws then count among the earlier frames' of the next), the
    // capture read to its end.
    let mut last = None;
    while let Some(done) = reader.next_frame(true, true)? {
        last = Some(done);
    }
    match last {
        Some(done) => reader.finish(done),
        None => Err(ImportError::Frame(
            file.into(),
            "the capture has no complete frame (no buffer swap)".into(),
        )),
    }
}

/// A streaming import: the calls read once, from the first, the GL state
/// carried from frame to frame, and frames imported in order as they are
/// asked for ([`Reader::frame`]).
pub struct Reader<I> {
    calls: I,
    file: PathBuf,
    skip_unsupported: bool,
    ctx: Context,
    /// The frame being read (the complete frames read so far).
    frame: u64,
    cur: FrameBuild,
    /// Calls not modelled so far, by name.
    unmodelled: BTreeMap<String, u64>,
    /// Unsupported draws (display lists, shader programs) of the frames
    /// before the current one, by feature.
    earlier: BTreeMap<String, u64>,
}

impl<I: Iterator<Item = Result<Call, CaptureError>>> Reader<I> {
    /// A reader of `calls` (read from `file`).
    pub fn new(
        calls: impl IntoIterator<IntoIter = I, Item = Result<Call, CaptureError>>,
        file: &Path,
        skip_unsupported: bool,
    ) -> Self {
        Reader {
            calls: calls.into_iter(),
            file: file.into(),
            skip_unsupported,
            ctx: Context::default(),
            frame: 0,
            cur: FrameBuild::default(),
            unmodelled: BTreeMap::new(),
            earlier: BTreeMap::new(),
        }
    }

    /// Import frame `n`, reading on to its swap (the frames between are
    /// read, their state tracked, their draws not recorded). `n` must not
    /// be a frame already read.
    pub fn frame(&mut self, n: u64) -> Result<Imported, ImportError> {
        assert!(n >= self.frame, "frame {n} was read already");
        loop {
            let here = self.frame;
            match self.next_frame(here == n, false)? {
                Some(done) if here == n => return self.finish(done),
                Some(_) => {}
                None => {
                    let read = self.frame;
                    return Err(ImportError::Frame(
                        self.file.clone(),
                        format!(
                            "frame {n} is past the end: the capture has {read} complete frames \
                             (0 to {})",
                            read.saturating_sub(1)
                        ),
                    ));
                }
            }
        }
    }

    /// Read the calls to the next swap, tracking the state and, if
    /// `record`, recording the frame's draws: the frame finished, `None`
    /// at the capture's end. The frame's unsupported draws count among
    /// the earlier frames' of the next: all of them if `all`, else those
    /// the tracker refuses without recording (immediate mode, display
    /// lists), as when the frames before one imported are not recorded.
    fn next_frame(&mut self, record: bool, all: bool) -> Result<Option<Finished>, ImportError> {
        for call in self.calls.by_ref() {
            let call = call?;
            let cur = &mut self.cur;
            match self
                .ctx
                .apply(&call)
                .map_err(|e| ImportError::Call(self.file.clone(), e))?
            {
                Effect::Modelled => {}
                Effect::Unmodelled(n) => *self.unmodelled.entry(n).or_default() += 1,
                Effect::Draw if record => match draw::record(&self.ctx, &call) {
                    Ok(Ok(rec)) => cur.draws.push(rec),
                    Ok(Err(feature)) => cur.unsupported(&call, feature, false),
                    Err(e) => {
                        cur.error.get_or_insert(e);
                    }
                },
                Effect::UnsupportedDraw(f) => cur.unsupported(&call, f, true),
                Effect::Draw => {}
                Effect::FrameEnd => {
                    let next = FrameBuild {
                        first_call: call.no + 1,
                        ..Default::default()
                    };
                    let build = std::mem::replace(&mut self.cur, next);
                    let before = self.earlier.clone();
                    let counted = if all {
                        &build.unsupported
                    } else {
                        &build.refused
                    };
                    for (f, n) in counted {
                        *self.earlier.entry(f.clone()).or_default() += n;
                    }
                    let done = Finished {
                        index: self.frame,
                        build,
                        unmodelled: self.unmodelled.clone(),
                        earlier: before,
                        last_call: call.no,
                    };
                    self.frame += 1;
                    return Ok(Some(done));
                }
            }
        }
        Ok(None)
    }

    /// A frame finished: its errors, or its scene placed in the frame.
    fn finish(&self, done: Finished) -> Result<Imported, ImportError> {
        let file = self.file.as_path();
        let Finished {
            index,
            build,
            unmodelled,
            earlier,
            last_call,
        } = done;
        if let Some(e) = build.error {
            return Err(ImportError::Call(file.into(), e));
        }
        if let (Some(e), false) = (&build.first_unsupported, self.skip_unsupported) {
            let mut e = e.clone();
            e.message += " (--skip-unsupported counts such draws and goes on)";
            return Err(ImportError::Call(file.into(), e));
        }
        let (width, height) = frame_size(&build.draws, &self.ctx).ok_or_else(|| {
            ImportError::Frame(
                file.into(),
                format!("frame {index} has no viewport (glViewport)"),
            )
        })?;
        let built = scene::scene_of(&build.draws, width, height, file, index)
            .map_err(|e| ImportError::Call(file.into(), e))?;
        Ok(Imported {
            scene: built.scene,
            width,
            height,
            frame: index,
            calls: (build.first_call, last_call),
            frames_read: self.frame,
            draw_calls: build.draws.len() as u64,
            draw_call_numbers: build.draws.iter().map(|d| d.call).collect(),
            triangles: build.draws.iter().map(|d| d.triangles).sum(),
            unsupported: build.unsupported,
            unsupported_in_earlier_frames: earlier,
            unmodelled,
            textures: built.infos,
            texture_ids: built.texture_ids,
            material_draws: built.material_draws,
        })
    }
}

/// The frame's size: the extent of its draws' viewports (the current one
/// without draws), so the window (wasp: the engine's full-window viewport
/// is the frame).
fn frame_size(draws: &[DrawRec], ctx: &Context) -> Option<(u32, u32)> {
    let ext = |v: &[i64; 4]| (v[0] + v[2], v[1] + v[3]);
    let (w, h) = if draws.is_empty() {
        ext(&ctx.state.viewport)
    } else {
        draws
            .iter()
            .map(|d| ext(&d.fixed.viewport))
            .fold((0, 0), |a, b| (a.0.max(b.0), a.1.max(b.1)))
    };
    (w > 0 && h > 0 && w <= 16384 && h <= 16384).then_some((w as u32, h as u32))
}

#[cfg(test)]
pub(crate) mod tests {
    use super::super::args::test_calls::*;
    use super::super::enums as gl;
    use super::*;
    use crate::raster::{rasterize, RasterOptions};
    use wasp_gltrace::Value;

    /// A frame of a 64x64 window: glOrtho(0, 64, 0, 64, -1, 1), depth test
    /// with `func`, then each square (x0, y0, x1, y1, z) of `squares` drawn
    /// as GL_QUADS in that order; one swap.
    fn frame(func: Option<i64>, squares: &[[f32; 5]]) -> Vec<Call> {
        let i = Value::SInt;
        let mut c = vec![
            call(0, "glXMakeCurrent", vec![]),
            call(0, "glViewport", vec![i(0), i(0), i(64), i(64)]),
            call(0, "glClear", vec![Value::Bitmask(0x4100)]),
            call(0, "glMatrixMode", vec![e(gl::PROJECTION)]),
            call(
                0,
                "glOrtho",
                vec![f(0.0), f(64.0), f(0.0), f(64.0), f(-1.0), f(1.0)],
            ),
            call(0, "glEnableClientState", vec![e(0x8074)]),
        ];
        if let Some(func) = func {
            c.push(call(0, "glEnable", vec![e(gl::DEPTH_TEST)]));
            c.push(call(0, "glDepthFunc", vec![e(func)]));
        }
        for s in squares {
            let [x0, y0, x1, y1, z] = *s;
            let v = floats(&[x0, y0, z, x1, y0, z, x1, y1, z, x0, y1, z]);
            c.push(call(
                0,
                "glVertexPointer",
                vec![i(3), e(gl::FLOAT), i(0), v],
            ));
            c.push(call(0, "glDrawArrays", vec![e(gl::QUADS), i(0), i(4)]));
        }
        c.push(call(0, "glXSwapBuffers", vec![]));
        for (n, k) in c.iter_mut().enumerate() {
            k.no = n as u64;
        }
        c
    }

    /// Import `calls`' last frame and rasterize it on one thread.
    pub(crate) fn run(calls: Vec<Call>) -> (Imported, crate::raster::Frame) {
        let imp = import(
            calls.into_iter().map(Ok),
            Path::new("t.trace"),
            ImportOptions::default(),
        )
        .unwrap();
        let opts = RasterOptions {
            threads: 1,
            ..Default::default()
        };
        let f = rasterize(&imp.scene, imp.width, imp.height, &opts).unwrap();
        (imp, f)
    }

    #[test]
    fn a_near_square_drawn_first_rejects_exactly_its_area_of_the_far_one() {
        // GL_LESS; the near square (z = 0.5: window depth 0.25) covers the
        // bottom-left 32x32 pixels, the far one (window depth 0.75) all
        // 64x64. Each square's two triangles share a diagonal, so the 16
        // quads a 32-pixel diagonal crosses hold a fragment of each.
        let near = [0.0, 0.0, 32.0, 32.0, 0.5];
        let far = [0.0, 0.0, 64.0, 64.0, -0.5];
        let (imp, f) = run(frame(Some(gl::NEVER + 1), &[near, far]));
        assert_eq!(
            (imp.width, imp.height, imp.draw_calls, imp.triangles),
            (64, 64, 2, 4)
        );
        let near_quads = 16 * 16 + 16;
        assert_eq!(f.stats.materials[0].warps, near_quads);
        // The far square: its 256 quads under the near one, and the 16
        // duplicates of its diagonal there, rejected; the rest shaded.
        assert_eq!(f.stats.quads_rejected_early_z, 16 * 16 + 16);
        assert_eq!(f.stats.materials[1].warps, 32 * 32 - 16 * 16 + 16);
        assert_eq!(f.stats.positions, 32 * 32);
        // Far first: nothing is rejected; without the depth test neither.
        let (_, g) = run(frame(Some(gl::NEVER + 1), &[far, near]));
        assert_eq!(g.stats.quads_rejected_early_z, 0);
        assert_eq!(g.stats.warps, near_quads + 32 * 32 + 32);
        let (_, h) = run(frame(None, &[near, far]));
        assert_eq!(
            (h.stats.quads_rejected_early_z, h.stats.warps),
            (0, g.stats.warps)
        );
        // GL_GREATER against the cleared depth 1: no fragment passes, every
        // covered quad is rejected.
        let (_, k) = run(frame(Some(gl::NEVER + 4), &[near, far]));
        assert_eq!(k.stats.warps, 0);
        assert_eq!(k.stats.quads_rejected_early_z, near_quads + 32 * 32 + 32);
    }

    #[test]
    fn frames_are_selected_and_bad_ones_say_how_many_there_are() {
        let one = frame(None, &[[0.0, 0.0, 8.0, 8.0, 0.0]]);
        let mut two = one.clone();
        two.extend(frame(
            None,
            &[[0.0, 0.0, 8.0, 8.0, 0.0], [8.0, 8.0, 16.0, 16.0, 0.0]],
        ));
        for (n, k) in two.iter_mut().enumerate() {
            k.no = n as u64;
        }
        let path = Path::new("t.trace");
        let last = import(
            two.clone().into_iter().map(Ok),
            path,
            ImportOptions::default(),
        )
        .unwrap();
        assert_eq!((last.frame, last.draw_calls, last.frames_read), (1, 2, 2));
        let opts = ImportOptions {
            frame: Some(0),
            ..Default::default()
        };
        let first = import(two.clone().into_iter().map(Ok), path, opts).unwrap();
        assert_eq!((first.frame, first.draw_calls, first.calls.0), (0, 1, 0));
        let opts = ImportOptions {
            frame: Some(2),
            ..Default::default()
        };
        let msg = import(two.clone().into_iter().map(Ok), path, opts)
            .unwrap_err()
            .to_string();
        assert!(
            msg.contains("t.trace") && msg.contains("2 complete frames (0 to 1)"),
            "{msg}"
        );
        // A draw with no vertex array: an error naming the call.
        let mut bad = one.clone();
        bad.retain(|c| &*c.name != "glEnableClientState");
        let err = import(bad.into_iter().map(Ok), path, ImportOptions::default()).unwrap_err();
        assert!(
            err.to_string().contains("glDrawArrays): no vertex array"),
            "{err}"
        );
        // A display list: an error, or with skip_unsupported a count.
        let mut imm = one;
        imm.insert(7, call(7, "glCallList", vec![Value::UInt(1)]));
        let err = import(
            imm.clone().into_iter().map(Ok),
            path,
            ImportOptions::default(),
        );
        assert!(err.unwrap_err().to_string().contains("display list"));
        let opts = ImportOptions {
            skip_unsupported: true,
            ..Default::default()
        };
        let ok = import(imm.clone().into_iter().map(Ok), path, opts).unwrap();
        assert_eq!(ok.unsupported.values().sum::<u64>(), 1);
        // Imported after it, that frame's draw is counted as earlier.
        let mut later = imm.clone();
        later.extend(frame(None, &[[0.0, 0.0, 8.0, 8.0, 0.0]]));
        let next = import(later.into_iter().map(Ok), path, ImportOptions::default()).unwrap();
        assert!(next.unsupported.is_empty());
        let want = [("a display list".to_string(), 1)];
        assert_eq!(next.unsupported_in_earlier_frames, want.into());
        assert_eq!(ok.unmodelled.get("glXMakeCurrent"), Some(&1));
    }

    #[test]
    fn a_reader_imports_frames_in_order_as_single_imports_do() {
        // Three frames: 1, 2 and 1 squares; the third past the range read.
        let mut calls = frame(None, &[[0.0, 0.0, 8.0, 8.0, 0.0]]);
        calls.extend(frame(
            None,
            &[[0.0, 0.0, 8.0, 8.0, 0.0], [8.0, 8.0, 16.0, 16.0, 0.0]],
        ));
        calls.extend(frame(None, &[[0.0, 0.0, 4.0, 4.0, 0.0]]));
        for (n, k) in calls.iter_mut().enumerate() {
            k.no = n as u64;
        }
        let path = Path::new("t.trace");
        let mut reader = Reader::new(calls.clone().into_iter().map(Ok), path, false);
        for n in [1, 2] {
            let one = import(
                calls.clone().into_iter().map(Ok),
                path,
                ImportOptions {
                    frame: Some(n),
                    ..Default::default()
                },
            )
            .unwrap();
            let got = reader.frame(n).unwrap();
            assert_eq!(
                (got.frame, got.calls, got.frames_read, got.draw_calls),
                (one.frame, one.calls, one.frames_read, one.draw_calls)
            );
            assert_eq!(got.scene, one.scene);
            assert_eq!(got.unmodelled, one.unmodelled);
        }
        let msg = reader.frame(3).unwrap_err().to_string();
        assert!(msg.contains("3 complete frames (0 to 2)"), "{msg}");
    }

    #[test]
    fn a_draw_in_a_sub_viewport_lands_in_its_rectangle_and_no_further() {
        // A 64x64 window: a 2x2 square at its bottom-left corner, then a
        // draw whose viewport is the top-right quarter (window x 32..64,
        // y 32..64: frame rows 0..32) with a square overflowing the view
        // volume on every side: clipped to the viewport, exactly 32 x 32
        // pixels, all in the top-right 32x32 tile.
        let mut calls = frame(None, &[[0.0, 0.0, 2.0, 2.0, 0.0]]);
        let i = Value::SInt;
        let swap = calls.pop().unwrap();
        calls.push(call(0, "glViewport", vec![i(32), i(32), i(32), i(32)]));
        let big = floats(&[
            -10.0, -10.0, 0.0, 80.0, -10.0, 0.0, 80.0, 80.0, 0.0, -10.0, 80.0, 0.0,
        ]);
        calls.push(call(
            0,
            "glVertexPointer",
            vec![i(3), e(gl::FLOAT), i(0), big],
        ));
        calls.push(call(0, "glDrawArrays", vec![e(gl::QUADS), i(0), i(4)]));
        calls.push(swap);
        let imp = import(
            calls.into_iter().map(Ok),
            Path::new("t"),
            ImportOptions::default(),
        )
        .unwrap();
        assert_eq!((imp.width, imp.height), (64, 64));
        let opts = RasterOptions {
            tile: 32,
            threads: 1,
            ..Default::default()
        };
        let f = rasterize(&imp.scene, 64, 64, &opts).unwrap();
        assert_eq!(f.stats.materials[1].pixels, 32 * 32);
        let at = |x: u32, y: u32| f.trace.tiles().iter().find(|t| (t.tx(), t.ty()) == (x, y));
        assert_eq!(
            at(1, 0).unwrap().quad_count() as u64,
            f.stats.materials[1].warps
        );
        let corner = at(0, 1).unwrap();
        assert_eq!(
            corner.quad_count(),
            2,
            "one quad: a fragment of each triangle"
        );
        assert!(at(0, 0).is_none() && at(1, 1).is_none());
    }
}
