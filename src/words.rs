//! Scenes and cameras as 32-bit words: what a firmware's build writes as constants from a
//! scene it has built and proven on the host ([`Scene::write_words`](crate::Scene::write_words),
//! [`Camera::write_words`](crate::Camera::write_words)), and what the firmware reads back
//! ([`Scene::from_words`](crate::Scene::from_words),
//! [`Camera::from_words`](crate::Camera::from_words)) without building or proving anything: the
//! chip runs no scene build, no range proof and no `f64` arithmetic for them.
//!
//! The words are each stored number's bits ([`Bits`]) and each choice's place in its list, field
//! by field, after a tag naming what they hold and its format and before a checksum of them
//! all. Words a scene or a camera of the format did not write are refused, so that by this road
//! too only a scene the range proof holds reaches the tracer: a [`crate::Scene`] comes only from
//! a description the build has proven.

crate::phase::declare_phase!(Some(crate::phase::Phase::Words));

use crate::methods::{
    BiasMethod, MethodName, Methods, RayMethod, RootMethod, SphereMethod, TriangleMethod,
};
use crate::scalar::{Bits, NumberBits};
use crate::uses::Uses;
use core::fmt;

/// Words that are not a scene's or a camera's as [`Scene::write_words`](crate::Scene::write_words) and [`Camera::write_words`](crate::Camera::write_words) write them, in the format and
/// within the capacities and parts ([`crate::Uses`]) asked for.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct WordsError {
    /// What the words were to hold: `"scene"` or `"camera"`.
    pub what: &'static str,
    /// The format asked for.
    pub format: &'static str,
}

impl fmt::Display for WordsError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        // Piece by piece: a `str`'s `Display` pads, and a firmware would link the padding.
        for piece in [
            "the words are not a ",
            self.what,
            " proven in ",
            self.format,
            " within these capacities and parts: build them again from the scene (",
            if self.what == "camera" {
                "Camera"
            } else {
                "Scene"
            },
            "::write_words)",
        ] {
            f.write_str(piece)?;
        }
        Ok(())
    }
}

/// A scene and its camera built and proven on the host, as the words a firmware keeps in
/// flash: what a build script's `obscura_scene::build` writes as a constant, and what the chip
/// reads back with one call, [`Scene::from_proven`](crate::Scene::from_proven), building and
/// proving nothing.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ProvenScene<'a> {
    /// The scene's words ([`Scene::write_words`](crate::Scene::write_words)).
    pub scene: &'a [u32],
    /// Its meshes' words, read in place ([`crate::mesh::MeshWords`]).
    pub meshes: &'static [u32],
    /// The camera's words, at the display's size
    /// ([`Camera::write_words`](crate::Camera::write_words)).
    pub camera: &'a [u32],
}

/// A value that goes to words and comes back the same.
pub(crate) trait Words: Sized {
    /// Writes the value's words.
    fn put(&self, out: &mut Writer<'_>);
    /// Reads a value; where the words are not one, the reader is refused ([`Reader::refuse`])
    /// and the value is whatever they gave. No read fails on its own, so that reading costs
    /// a firmware little code: the whole is refused at the end.
    fn take<const IN_PLACE: bool>(input: &mut Reader<'_, IN_PLACE>) -> Self;
}

/// Where words go, summed on their way.
pub(crate) struct Writer<'a> {
    sink: &'a mut dyn FnMut(u32),
    sum: u32,
}

impl<'a> Writer<'a> {
    /// A writer to `sink` that sums for no one: what counts the words of a value.
    #[cfg(test)]
    pub(crate) fn counting(sink: &'a mut dyn FnMut(u32)) -> Self {
        Self { sink, sum: 0 }
    }

    /// Writes `word`.
    pub(crate) fn word(&mut self, word: u32) {
        self.sum = checksum(self.sum, word);
        (self.sink)(word);
    }
}

/// Where words come from, whether they have been found not to be what was read, and the parts
/// of the tracer the value read may use ([`Uses`]: a kind of shape it leaves out is refused
/// where its tag is read, so that no code to read it is linked).
///
/// `IN_PLACE` reads each word inline: what a mesh's node or triangle, read from flash each time
/// the tracer tests it, is read by; a scene, read once, is read out of line.
pub(crate) struct Reader<'a, const IN_PLACE: bool = false> {
    words: &'a [u32],
    refused: bool,
    parts: Uses,
}

impl<'a, const IN_PLACE: bool> Reader<'a, IN_PLACE> {
    /// A reader of `words`, for a value that may use every part.
    pub(crate) const fn over(words: &'a [u32]) -> Self {
        Self {
            words,
            refused: false,
            parts: Uses::EVERYTHING,
        }
    }

    /// Whether the value read may use `part`.
    #[inline(always)]
    pub(crate) const fn allows(&self, part: Uses) -> bool {
        self.parts.contains(part)
    }

    /// The value read may use only `parts` (a scene of a tracer of these parts).
    pub(crate) fn allow_only(&mut self, parts: Uses) {
        self.parts = parts;
    }

    /// The next word; past the end, 0 and the reader refused. Read inline by an `IN_PLACE`
    /// reader, else out of line: reading a scene is mostly calls of it, one per word, and a
    /// firmware's image is smaller so.
    #[inline(always)]
    pub(crate) fn word(&mut self) -> u32 {
        if IN_PLACE {
            self.next()
        } else {
            self.next_out_of_line()
        }
    }

    #[inline(never)]
    fn next_out_of_line(&mut self) -> u32 {
        self.next()
    }

    #[inline(always)]
    fn next(&mut self) -> u32 {
        if let Some((&first, rest)) = self.words.split_first() {
            self.words = rest;
            first
        } else {
            self.refuse();
            0
        }
    }

    /// The next word as a count of at most `capacity`; beyond it, 0 and the reader refused.
    pub(crate) fn count(&mut self, capacity: usize) -> usize {
        match usize::try_from(self.word()) {
            Ok(n) if n <= capacity => n,
            _ => {
                self.refuse();
                0
            }
        }
    }

    /// The words are not what is being read.
    pub(crate) fn refuse(&mut self) {
        self.refused = true;
    }
}

/// FNV-1a over 32-bit words: `word` added to `sum`. Each step maps the sum one to one for a
/// given word, and a changed word changes the sum, so a changed word always changes the checksum.
const fn checksum(sum: u32, word: u32) -> u32 {
    (sum ^ word).wrapping_mul(0x0100_0193)
}

/// The checksum of `words`. Out of line, and one copy for every read.
#[inline(never)]
fn checksum_of(words: &[u32]) -> u32 {
    words.iter().fold(0, |sum, &word| checksum(sum, word))
}

/// The tag of words holding `what` in format `S`: the checksum of their names, a byte a word.
fn tag<S: Bits>(what: &str) -> u32 {
    what.bytes()
        .chain(*b"/")
        .chain(S::NAME.bytes())
        .fold(0x811c_9dc5, |sum, byte| checksum(sum, u32::from(byte)))
}

/// Writes `value`, which holds `what` in format `S`, to `sink`: its tag, its words, the checksum.
pub(crate) fn write<S: Bits>(what: &str, value: &impl Words, sink: &mut dyn FnMut(u32)) {
    write_with::<S>(what, sink, |out| value.put(out));
}

/// Writes what `put` writes, which holds `what` in format `S`, to `sink`: its tag, its words,
/// the checksum.
pub(crate) fn write_with<S: Bits>(
    what: &str,
    sink: &mut dyn FnMut(u32),
    put: impl FnOnce(&mut Writer<'_>),
) {
    let mut out = Writer { sink, sum: 0 };
    out.word(tag::<S>(what));
    put(&mut out);
    let sum = out.sum;
    (out.sink)(sum);
}

/// The words [`write()`] wrote of `what` in format `S`, between the tag and the checksum, where
/// they are such words.
pub(crate) fn body<'a, S: Bits>(
    what: &'static str,
    words: &'a [u32],
) -> Result<&'a [u32], WordsError> {
    let refused = WordsError {
        what,
        format: S::NAME,
    };
    let (&sum, body) = words.split_last().ok_or(refused)?;
    if body.first() != Some(&tag::<S>(what)) || checksum_of(body) != sum {
        return Err(refused);
    }
    Ok(body.get(1..).unwrap_or_default())
}

/// Reads what [`write()`] wrote of `what` in format `S`. Out of line: with it inlined, a
/// firmware's image is larger.
#[inline(never)]
pub(crate) fn read<S: Bits, T: Words>(what: &'static str, words: &[u32]) -> Result<T, WordsError> {
    let refused = WordsError {
        what,
        format: S::NAME,
    };
    let mut input = Reader::<false>::over(body::<S>(what, words)?);
    let value = T::take(&mut input);
    if input.refused || !input.words.is_empty() {
        Err(refused)
    } else {
        Ok(value)
    }
}

impl<S: NumberBits> Words for S {
    #[allow(clippy::cast_possible_truncation, reason = "word by word")]
    fn put(&self, out: &mut Writer<'_>) {
        let bits = self.to_bits();
        out.word(bits as u32);
        if S::WORDS == 2 {
            out.word((bits >> 32) as u32);
        }
    }

    fn take<const IN_PLACE: bool>(input: &mut Reader<'_, IN_PLACE>) -> Self {
        let low = u64::from(input.word());
        let high = if S::WORDS == 2 {
            u64::from(input.word())
        } else {
            0
        };
        S::from_bits(low | high << 32)
    }
}

/// Words for small unsigned integers: one word each.
macro_rules! words_of_integer {
    ($($t:ty),*) => {$(
        impl Words for $t {
            fn put(&self, out: &mut Writer<'_>) {
                out.word(u32::from(*self));
            }

            fn take<const IN_PLACE: bool>(input: &mut Reader<'_, IN_PLACE>) -> Self {
                Self::try_from(input.word()).unwrap_or_else(|_| {
                    input.refuse();
                    0
                })
            }
        }
    )*};
}
words_of_integer!(u8, u16, u32);

impl Words for i64 {
    #[allow(
        clippy::cast_possible_truncation,
        clippy::cast_sign_loss,
        reason = "word by word, low first"
    )]
    fn put(&self, out: &mut Writer<'_>) {
        let bits = *self as u64;
        out.word(bits as u32);
        out.word((bits >> 32) as u32);
    }

    #[allow(clippy::cast_possible_wrap, reason = "the two words are the bits")]
    fn take<const IN_PLACE: bool>(input: &mut Reader<'_, IN_PLACE>) -> Self {
        let low = u64::from(input.word());
        (u64::from(input.word()) << 32 | low) as Self
    }
}

impl Words for bool {
    fn put(&self, out: &mut Writer<'_>) {
        out.word(u32::from(*self));
    }

    fn take<const IN_PLACE: bool>(input: &mut Reader<'_, IN_PLACE>) -> Self {
        match input.word() {
            0 => false,
            1 => true,
            _ => {
                input.refuse();
                false
            }
        }
    }
}

impl<T: Words> Words for Option<T> {
    fn put(&self, out: &mut Writer<'_>) {
        out.word(u32::from(self.is_some()));
        if let Some(value) = self {
            value.put(out);
        }
    }

    fn take<const IN_PLACE: bool>(input: &mut Reader<'_, IN_PLACE>) -> Self {
        bool::take(input).then(|| T::take(input))
    }
}

impl<T: Words, const N: usize> Words for [T; N] {
    fn put(&self, out: &mut Writer<'_>) {
        for value in self {
            value.put(out);
        }
    }

    fn take<const IN_PLACE: bool>(input: &mut Reader<'_, IN_PLACE>) -> Self {
        core::array::from_fn(|_| T::take(input))
    }
}

/// Words for a struct, field by field: `words_of_struct!(Sphere<S> { center, radius })`. Every
/// field must be listed (reading builds the struct from them). The format is a [`Bits`], or
/// where a narrow format's numbers are stored too, a [`NumberBits`] if it is named so:
/// `words_of_struct!(Rgb<S: NumberBits> { r, g, b })`.
macro_rules! words_of_struct {
    ($ty:ident <$t:ident> { $($field:ident),* $(,)? }) => {
        $crate::words::words_of_struct!($ty<$t: Bits> { $($field),* });
    };
    ($ty:ident $(<$t:ident: $bound:ident>)? { $($field:ident),* $(,)? }) => {
        impl$(<$t: $crate::scalar::$bound>)? $crate::words::Words for $ty$(<$t>)? {
            fn put(&self, out: &mut $crate::words::Writer<'_>) {
                $($crate::words::Words::put(&self.$field, out);)*
            }

            fn take<const IN_PLACE: bool>(input: &mut $crate::words::Reader<'_, IN_PLACE>) -> Self {
                Self {
                    $($field: $crate::words::Words::take(input),)*
                }
            }
        }
    };
}
pub(crate) use words_of_struct;

/// Words for an enum: its variant's place among those listed (every one, in order), then its
/// fields: `words_of_enum!(Cone<S> { Everywhere, Within { axis, cos } })`, a variant with one
/// unnamed field as `Solid(colour)`. A variant may name the part of the tracer it needs
/// (`Triangle(triangle) if Uses::TRIANGLES`): read where the reader does not allow it
/// ([`Reader::allows`]), it refuses the reader, as a place beyond the list does, and after the
/// first no code to read its fields is linked.
macro_rules! words_of_enum {
    ($ty:ident $(<$t:ident>)? {
        $first:ident $(($first_inner:ident))? $({ $($first_field:ident),* })? $(if $first_part:expr)?
        $(, $variant:ident $(($inner:ident))? $({ $($field:ident),* })? $(if $part:expr)?)* $(,)?
    }) => {
        impl$(<$t: $crate::scalar::Bits>)? $crate::words::Words for $ty$(<$t>)? {
            #[allow(unused_assignments, reason = "the place after the last variant")]
            fn put(&self, out: &mut $crate::words::Writer<'_>) {
                let mut place = 0_u32;
                if let Self::$first $(($first_inner))? $({ $($first_field),* })? = self {
                    out.word(place);
                    $($crate::words::Words::put($first_inner, out);)?
                    $($($crate::words::Words::put($first_field, out);)*)?
                    return;
                }
                $(
                    place += 1;
                    if let Self::$variant $(($inner))? $({ $($field),* })? = self {
                        out.word(place);
                        $($crate::words::Words::put($inner, out);)?
                        $($($crate::words::Words::put($field, out);)*)?
                        return;
                    }
                )*
            }

            #[allow(unused_assignments, reason = "the place after the last variant")]
            fn take<const IN_PLACE: bool>(input: &mut $crate::words::Reader<'_, IN_PLACE>) -> Self {
                let tag = input.word();
                let mut place = 0_u32;
                $(
                    place += 1;
                    if tag == place && true $(&& input.allows($part))? {
                        return Self::$variant
                            $(({ let $inner = $crate::words::Words::take(input); $inner }))?
                            $({ $($field: $crate::words::Words::take(input)),* })?;
                    }
                )*
                if tag != 0 || !(true $(&& input.allows($first_part))?) {
                    input.refuse();
                }
                Self::$first
                    $(({ let $first_inner = $crate::words::Words::take(input); $first_inner }))?
                    $({ $($first_field: $crate::words::Words::take(input)),* })?
            }
        }
    };
}
pub(crate) use words_of_enum;

// The methods: each choice as its place in its list.
words_of_struct!(Methods {
    sphere,
    triangle,
    roots,
    rays,
    bias
});

/// Words for choices: each as its place in [`MethodName::ALL`].
macro_rules! words_of_choice {
    ($($ty:ty),*) => {$(
        impl Words for $ty {
            fn put(&self, out: &mut Writer<'_>) {
                let place = Self::ALL.iter().position(|(m, _)| m == self);
                out.word(place.and_then(|p| u32::try_from(p).ok()).unwrap_or(u32::MAX));
            }

            fn take<const IN_PLACE: bool>(input: &mut Reader<'_, IN_PLACE>) -> Self {
                let place = usize::try_from(input.word()).unwrap_or(usize::MAX);
                Self::ALL.get(place).map_or_else(
                    || {
                        input.refuse();
                        Self::default()
                    },
                    |&(m, _)| m,
                )
            }
        }
    )*};
}
words_of_choice!(
    SphereMethod,
    TriangleMethod,
    RootMethod,
    RayMethod,
    BiasMethod
);

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scalar::Precision;
    use crate::scene::Scene;
    use crate::test_util::each_built_in_scene;
    use crate::uses::Parts;
    use crate::{Camera, scalar};

    fn words_of(write: impl FnOnce(&mut dyn FnMut(u32))) -> Vec<u32> {
        let mut words = Vec::new();
        write(&mut |w| words.push(w));
        words
    }

    /// Every built-in scene that `S` holds, by every variant of the methods, and its camera
    /// read back from their words are the same.
    fn round_trip<S: Bits>() {
        each_built_in_scene::<S>(32, |name, methods, scene, camera| {
            let words = words_of(|sink| scene.write_words(sink));
            let back = Scene::<S, 8, 4, 8>::from_words(&words);
            assert_eq!(back.as_ref(), Ok(scene), "{name} {methods} in {}", S::NAME);
            let words = words_of(|sink| camera.write_words(sink));
            assert_eq!(Camera::<S>::from_words(&words).as_ref(), Ok(camera));
        });
    }

    #[test]
    fn scenes_and_cameras_read_back_from_their_words_in_every_format() {
        macro_rules! each {
            (fixed { $($f:ident => $raw:ident,)* } float { $($v:ident => $t:ty,)* }) => {
                $(round_trip::<scalar::Fx<fixed::types::$raw>>();)*
                $(round_trip::<$t>();)*
            };
        }
        crate::for_each_format!(each);
    }

    /// A tracer of spheres and planes by the lecture's methods (the methods' bits, which the
    /// test below checks, written out: a constant cannot call `Uses::methods`).
    #[derive(Clone, Copy, Debug, PartialEq, Eq)]
    struct SpheresAndPlanes;

    impl Parts for SpheresAndPlanes {
        const USES: Uses = Uses::SPHERES
            .union(Uses::PLANES)
            .union(Uses::from_bits(0x2_a500));
    }

    /// The same with triangles in place of spheres.
    #[derive(Clone, Copy, Debug, PartialEq, Eq)]
    struct PlanesAndTriangles;

    impl Parts for PlanesAndTriangles {
        const USES: Uses = Uses::from_bits(
            SpheresAndPlanes::USES.bits() & !Uses::SPHERES.bits() | Uses::TRIANGLES.bits(),
        );
    }

    #[test]
    fn a_scene_reads_back_only_into_a_tracer_with_every_part_it_uses() {
        let parts = SpheresAndPlanes::USES;
        assert_eq!(
            parts,
            Uses::SPHERES
                .union(Uses::PLANES)
                .union(Uses::methods(&Methods::LECTURE))
        );
        let whitted = Scene::<f32, 8, 4, 8>::build(&crate::scenes::WHITTED).unwrap();
        let shapes = Scene::<f32, 8, 4, 8>::build(&crate::scenes::SHAPES).unwrap();
        assert!(parts.contains(whitted.uses()) && !parts.contains(shapes.uses()));
        let whitted_words = words_of(|sink| whitted.write_words(sink));
        let shapes_words = words_of(|sink| shapes.write_words(sink));
        let read = Scene::<f32, 8, 4, 8, SpheresAndPlanes>::from_words(&whitted_words);
        assert_eq!(read.map(|scene| scene.uses()), Ok(whitted.uses()));
        // Triangles, which the tracer leaves out; spheres, which a tracer of planes and
        // triangles does; stable spheres, the lecture's quadratic.
        assert!(Scene::<f32, 8, 4, 8, SpheresAndPlanes>::from_words(&shapes_words).is_err());
        assert!(Scene::<f32, 8, 4, 8, PlanesAndTriangles>::from_words(&shapes_words).is_err());
        let stable = Methods {
            sphere: SphereMethod::Stable,
            ..Methods::LECTURE
        };
        let whitted_stable =
            Scene::<f32, 8, 4, 8>::build_with(&crate::scenes::WHITTED, stable).unwrap();
        let words = words_of(|sink| whitted_stable.write_words(sink));
        assert!(Scene::<f32, 8, 4, 8, SpheresAndPlanes>::from_words(&words).is_err());
        // Several rays per pixel, and an area light.
        for desc in [
            crate::SceneDesc {
                samples: 4,
                ..crate::scenes::WHITTED
            },
            crate::scenes::SOFT,
        ] {
            let scene = Scene::<f32, 8, 4, 8>::build(&desc).unwrap();
            let words = words_of(|sink| scene.write_words(sink));
            assert!(!parts.contains(scene.uses()));
            assert!(Scene::<f32, 8, 4, 8, SpheresAndPlanes>::from_words(&words).is_err());
        }
    }

    #[test]
    fn a_camera_that_uses_what_the_tracer_lacks_is_refused_by_the_render() {
        use embedded_graphics::mock_display::MockDisplay;
        use embedded_graphics::pixelcolor::Rgb565;
        let whitted = Scene::<f32, 8, 4, 8>::build(&crate::scenes::WHITTED).unwrap();
        let words = words_of(|sink| whitted.write_words(sink));
        let scene = Scene::<f32, 8, 4, 8, SpheresAndPlanes>::from_words(&words).unwrap();
        // A lens, from another scene.
        let focus = Scene::<f32, 8, 4, 8>::build(&crate::scenes::FOCUS).unwrap();
        let camera = focus.camera(8, 8).unwrap();
        let mut line = [Rgb565::default(); 8];
        let mut display = MockDisplay::<Rgb565>::new();
        let frame = crate::Presentation::default();
        let refused = crate::render_frame(&scene, &camera, frame, &mut line, &mut [], &mut display);
        assert_eq!(
            refused,
            Err(crate::RenderError::TracerLacks {
                missing: Uses::LENS
            })
        );
        // Its own camera draws.
        let camera = scene.camera(8, 8).unwrap();
        let mut display = MockDisplay::<Rgb565>::new();
        crate::render_frame(&scene, &camera, frame, &mut line, &mut [], &mut display).unwrap();
    }

    #[test]
    fn a_proven_scene_and_its_camera_read_back_in_one_call() {
        type Read =
            Scene<crate::I16F16, 8, 4, 8, crate::Everything, crate::mesh::MeshWords<crate::I16F16>>;
        let scene = Scene::<crate::I16F16, 8, 4, 8>::build(&crate::scenes::WHITTED).unwrap();
        let camera = scene.camera(16, 16).unwrap();
        let leak = |words: Vec<u32>| -> &'static [u32] { words.leak() };
        let proven = ProvenScene {
            scene: leak(words_of(|sink| scene.write_words(sink))),
            meshes: leak(words_of(|sink| scene.write_mesh_words(sink))),
            camera: leak(words_of(|sink| camera.write_words(sink))),
        };
        let (back, back_camera) = Read::from_proven(&proven).unwrap();
        assert_eq!(words_of(|sink| back.write_words(sink)), proven.scene);
        assert_eq!(back_camera, camera);
        // Each part's words in another's place are refused, naming the part.
        let swapped = ProvenScene {
            scene: proven.camera,
            camera: proven.scene,
            ..proven
        };
        assert_eq!(Read::from_proven(&swapped).unwrap_err().what, "scene");
        let camera_as_meshes = ProvenScene {
            meshes: proven.camera,
            ..proven
        };
        assert_eq!(
            Read::from_proven(&camera_as_meshes).unwrap_err().what,
            "meshes"
        );
        let scene_as_camera = ProvenScene {
            camera: proven.scene,
            ..proven
        };
        assert_eq!(
            Read::from_proven(&scene_as_camera).unwrap_err().what,
            "camera"
        );
    }

    #[test]
    fn words_a_scene_of_the_format_did_not_write_are_refused() {
        let scene = Scene::<f32, 8, 4, 8>::build(&crate::scenes::WHITTED).unwrap();
        let words = words_of(|sink| scene.write_words(sink));
        let refused = |words: &[u32]| Scene::<f32, 8, 4, 8>::from_words(words).unwrap_err();
        // Each word changed, each word left off, none at all.
        for i in 0..words.len() {
            let mut changed = words.clone();
            changed[i] ^= 1 << (i % 32);
            assert_eq!(refused(&changed).what, "scene");
        }
        refused(&words[..words.len() - 1]);
        refused(&words[1..]);
        refused(&[]);
        // Another format, a camera, too few objects or too shallow a stack.
        assert_eq!(
            scalar::F32Approx::NAME,
            Scene::<scalar::F32Approx, 8, 4, 8>::from_words(&words)
                .unwrap_err()
                .format
        );
        assert_eq!(
            Camera::<f32>::from_words(&words).unwrap_err().what,
            "camera"
        );
        assert!(Scene::<f32, 1, 4, 8>::from_words(&words).is_err());
        assert!(Scene::<f32, 8, 4, 1>::from_words(&words).is_err());
        assert!(Scene::<f32, 8, 4, 8>::from_words(&words).is_ok());
        let message = refused(&[]).to_string();
        assert!(message.contains("scene proven in f32"), "{message}");
    }
}
