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

use crate::methods::MethodName;
use crate::scalar::Bits;
use core::fmt;

/// Words that are not a scene's or a camera's as [`crate::words`] writes them, in the format and
/// within the capacities asked for.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct WordsError {
    /// What the words were to hold: `"scene"` or `"camera"`.
    pub what: &'static str,
    /// The format asked for.
    pub format: &'static str,
}

impl fmt::Display for WordsError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "the words are not a {} proven in {} within these capacities: build them again \
             from the scene ({}::write_words)",
            self.what,
            self.format,
            if self.what == "camera" {
                "Camera"
            } else {
                "Scene"
            }
        )
    }
}

/// A value that goes to words and comes back the same.
pub(crate) trait Words: Sized {
    /// Writes the value's words.
    fn put(&self, out: &mut Writer<'_>);
    /// Reads a value, or `None` where the words are not one.
    fn take(input: &mut Reader<'_>) -> Option<Self>;
}

/// Where words go, summed on their way.
pub(crate) struct Writer<'a> {
    sink: &'a mut dyn FnMut(u32),
    sum: u32,
}

impl Writer<'_> {
    /// Writes `word`.
    pub(crate) fn word(&mut self, word: u32) {
        self.sum = checksum(self.sum, word);
        (self.sink)(word);
    }
}

/// Where words come from.
pub(crate) struct Reader<'a> {
    words: &'a [u32],
}

impl Reader<'_> {
    /// The next word, if there is one.
    pub(crate) fn word(&mut self) -> Option<u32> {
        let (&first, rest) = self.words.split_first()?;
        self.words = rest;
        Some(first)
    }

    /// The next word as a count of at most `capacity`.
    pub(crate) fn count(&mut self, capacity: usize) -> Option<usize> {
        usize::try_from(self.word()?)
            .ok()
            .filter(|&n| n <= capacity)
    }
}

/// FNV-1a over the word's bytes, low byte first, from `sum`.
const fn checksum(sum: u32, word: u32) -> u32 {
    let mut sum = sum;
    let mut shift = 0;
    while shift < u32::BITS {
        sum = (sum ^ ((word >> shift) & 0xff)).wrapping_mul(0x0100_0193);
        shift += 8;
    }
    sum
}

/// The tag of words holding `what` in format `S`: the checksum of their names.
fn tag<S: Bits>(what: &str) -> u32 {
    what.bytes()
        .chain(*b"/")
        .chain(S::NAME.bytes())
        .fold(0x811c_9dc5, |sum, byte| checksum(sum, u32::from(byte)))
}

/// Writes `value`, which holds `what` in format `S`, to `sink`: its tag, its words, the checksum.
pub(crate) fn write<S: Bits>(what: &str, value: &impl Words, sink: &mut dyn FnMut(u32)) {
    let mut out = Writer { sink, sum: 0 };
    out.word(tag::<S>(what));
    value.put(&mut out);
    let sum = out.sum;
    (out.sink)(sum);
}

/// Reads what [`write`] wrote of `what` in format `S`.
pub(crate) fn read<S: Bits, T: Words>(what: &'static str, words: &[u32]) -> Result<T, WordsError> {
    let refused = WordsError {
        what,
        format: S::NAME,
    };
    let (&sum, body) = words.split_last().ok_or(refused)?;
    if body.first() != Some(&tag::<S>(what)) || body.iter().fold(0, |s, &w| checksum(s, w)) != sum {
        return Err(refused);
    }
    let mut input = Reader {
        words: body.get(1..).unwrap_or_default(),
    };
    match T::take(&mut input) {
        Some(value) if input.words.is_empty() => Ok(value),
        _ => Err(refused),
    }
}

impl<S: Bits> Words for S {
    #[allow(clippy::cast_possible_truncation, reason = "word by word")]
    fn put(&self, out: &mut Writer<'_>) {
        let bits = self.to_bits();
        out.word(bits as u32);
        if S::WORDS == 2 {
            out.word((bits >> 32) as u32);
        }
    }

    fn take(input: &mut Reader<'_>) -> Option<Self> {
        let low = u64::from(input.word()?);
        let high = if S::WORDS == 2 {
            u64::from(input.word()?)
        } else {
            0
        };
        Some(S::from_bits(low | high << 32))
    }
}

/// Words for small unsigned integers and `bool`: one word each.
macro_rules! words_of_integer {
    ($($t:ty),*) => {$(
        impl Words for $t {
            fn put(&self, out: &mut Writer<'_>) {
                out.word(u32::from(*self));
            }

            fn take(input: &mut Reader<'_>) -> Option<Self> {
                Self::try_from(input.word()?).ok()
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
    fn take(input: &mut Reader<'_>) -> Option<Self> {
        let low = u64::from(input.word()?);
        Some((u64::from(input.word()?) << 32 | low) as Self)
    }
}

impl Words for bool {
    fn put(&self, out: &mut Writer<'_>) {
        out.word(u32::from(*self));
    }

    fn take(input: &mut Reader<'_>) -> Option<Self> {
        match input.word()? {
            0 => Some(false),
            1 => Some(true),
            _ => None,
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

    fn take(input: &mut Reader<'_>) -> Option<Self> {
        if bool::take(input)? {
            Some(Some(T::take(input)?))
        } else {
            Some(None)
        }
    }
}

impl<T: Words + Copy + Default, const N: usize> Words for [T; N] {
    fn put(&self, out: &mut Writer<'_>) {
        for value in self {
            value.put(out);
        }
    }

    fn take(input: &mut Reader<'_>) -> Option<Self> {
        let mut values = [T::default(); N];
        for value in &mut values {
            *value = T::take(input)?;
        }
        Some(values)
    }
}

/// A choice ([`MethodName`]) as its place in the list of choices.
pub(crate) fn put_choice<M: MethodName + PartialEq>(choice: M, out: &mut Writer<'_>) {
    let place = M::ALL.iter().position(|(m, _)| *m == choice);
    out.word(
        place
            .and_then(|p| u32::try_from(p).ok())
            .unwrap_or(u32::MAX),
    );
}

/// The choice at the place the next word gives.
pub(crate) fn take_choice<M: MethodName>(input: &mut Reader<'_>) -> Option<M> {
    let place = usize::try_from(input.word()?).ok()?;
    M::ALL.get(place).map(|(m, _)| *m)
}

/// Words for a struct, field by field: `words_of_struct!(Sphere<S> { center, radius })`. Every
/// field must be listed (reading builds the struct from them).
macro_rules! words_of_struct {
    ($ty:ident $(<$t:ident>)? { $($field:ident),* $(,)? }) => {
        impl$(<$t: $crate::scalar::Bits>)? $crate::words::Words for $ty$(<$t>)? {
            fn put(&self, out: &mut $crate::words::Writer<'_>) {
                $($crate::words::Words::put(&self.$field, out);)*
            }

            fn take(input: &mut $crate::words::Reader<'_>) -> Option<Self> {
                Some(Self {
                    $($field: $crate::words::Words::take(input)?,)*
                })
            }
        }
    };
}
pub(crate) use words_of_struct;

/// Words for choices ([`MethodName`]): `words_of_choice!(SphereMethod, RayMethod)`.
macro_rules! words_of_choice {
    ($($ty:ty),*) => {$(
        impl $crate::words::Words for $ty {
            fn put(&self, out: &mut $crate::words::Writer<'_>) {
                $crate::words::put_choice(*self, out);
            }

            fn take(input: &mut $crate::words::Reader<'_>) -> Option<Self> {
                $crate::words::take_choice(input)
            }
        }
    )*};
}
pub(crate) use words_of_choice;

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scalar::Scalar;
    use crate::scene::Scene;
    use crate::test_util::each_built_in_scene;
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
