use std::path::Path;

use super::*;
use crate::scene::LoadedScene;
use crate::sim::blows::Blow;

/// The samples, the blows and the bells' times of a run.
type Heard = (Vec<[f32; 2]>, Vec<Blow>, Vec<f64>);

/// `scenes/sound.ron` with its own seed, run once for the tests that
/// only read it.
fn heard() -> &'static Heard {
    static RUN: std::sync::OnceLock<Heard> = std::sync::OnceLock::new();
    RUN.get_or_init(|| listen(None))
}

/// Run `scenes/sound.ron` with a soundtrack: the samples and every blow.
fn listen(seed: Option<u64>) -> Heard {
    let text = include_str!("../../../../scenes/sound.ron");
    let mut scene = LoadedScene::from_str(text, Path::new("sound.ron"), None).unwrap();
    if let Some(s) = seed {
        scene.scene.seed = s;
    }
    let mut sim = scene.sim();
    let mut track = Soundtrack::new(scene.scene.seed);
    let (mut out, mut blows, mut bells) = (Vec::new(), Vec::new(), Vec::new());
    while sim.time() < scene.scene.duration - 1e-9 {
        let s = sim.step();
        blows.extend(s.blows.iter().cloned());
        if s.bell.is_some() {
            bells.push(s.t);
        }
        track.hear(&sim, &mut out);
    }
    track.finish(&sim, &mut out);
    (out, blows, bells)
}

/// RMS of both channels over 2 ms frames.
fn frames(x: &[[f32; 2]]) -> Vec<f32> {
    x.chunks(96)
        .map(|c| (c.iter().map(|s| s[0] * s[0] + s[1] * s[1]).sum::<f32>() / c.len() as f32).sqrt())
        .collect()
}

/// When the level jumps near `t`: of the 2 ms frames from 10 ms before
/// to 16 ms after it, the one that rises most over the 6 ms before it, if
/// that rise is over twice the median level of the 50 ms before `t`; as a
/// time from `t`.
fn rise(f: &[f32], t: f64) -> Option<f64> {
    let k = (t / 0.002).round() as usize;
    let mut before = f[k - 28..k - 3].to_vec();
    before.sort_by(f32::total_cmp);
    let base = before[before.len() / 2];
    let jump = |i: usize| f[i] - f[i - 3..i].iter().copied().fold(0.0, f32::max);
    let best = (k - 5..k + 8).max_by(|&a, &b| jump(a).total_cmp(&jump(b)))?;
    (jump(best) > 2.0 * base).then_some(best as f64 * 0.002 - t)
}

/// Every blow is heard when its glove struck (its contact's start plus the
/// sound's travel to your ear), over a crowd and breath at least 10 dB
/// quieter; and no blow comes without a sound. A soundtrack that played a
/// blow when it was judged (30 ms late) or at a fixed level misses this.
#[test]
fn each_blow_is_heard_when_it_lands() {
    let (x, blows, bells) = heard();
    let mut blows = blows.clone();
    blows.sort_by(|a, b| a.started.total_cmp(&b.started));
    assert_eq!(x.len(), 20 * RATE as usize, "the whole run, at {RATE} Hz");
    assert!(blows.len() >= 4, "the scene lands blows: {blows:?}");
    assert_eq!(bells.len(), 2, "{bells:?}");
    let f = frames(x);
    let mut sorted = f.clone();
    sorted.sort_by(f32::total_cmp);
    // The bed: what is always there (the crowd, the breath), the level
    // three frames in four exceed.
    let bed = sorted[sorted.len() / 4];
    assert!(bed > 1e-4, "a bed under the events: {bed}");
    for (i, b) in blows.iter().enumerate() {
        let k = (b.started / 0.002) as usize;
        let peak = f[k..k + 15].iter().copied().fold(0.0, f32::max);
        assert!(
            peak > 3.2 * bed,
            "a blow stands 10 dB over the bed: {peak} vs {bed}"
        );
        // A glove that meets the guard and then the head 15-40 ms later
        // is heard as one: judge the onset of the first.
        if i > 0 && b.started - blows[i - 1].started < 0.045 {
            continue;
        }
        let near = rise(&f, b.started);
        assert!(
            near.is_some_and(|d| (-0.004..0.008).contains(&d)),
            "a blow at {:.3} s ({:?} on {}, {:.1} N s): the sound rises at {near:?} s from it",
            b.started,
            b.kind,
            b.part,
            b.impulse
        );
    }
    // The bell is heard at both ends of the round.
    for &t in bells {
        let k = (t / 0.002) as usize;
        let peak = f[k..k + 25].iter().copied().fold(0.0, f32::max);
        assert!(peak > 3.2 * bed, "the bell at {t}: {peak} vs {bed}");
        assert!(t < 0.06 || rise(&f, t).is_some(), "the bell at {t}");
    }
}

/// A harder blow is louder: the loudness follows the impulse.
#[test]
fn a_harder_blow_sounds_louder() {
    let (x, blows, _) = heard();
    let f = frames(x);
    let peak = |b: &Blow| {
        let k = (b.started / 0.002) as usize;
        f[k..k + 15].iter().copied().fold(0.0, f32::max)
    };
    let hits: Vec<&Blow> = blows.iter().filter(|b| b.kind == BlowKind::Hit).collect();
    let soft = hits
        .iter()
        .min_by(|a, b| a.impulse.total_cmp(&b.impulse))
        .unwrap();
    let hard = hits
        .iter()
        .max_by(|a, b| a.impulse.total_cmp(&b.impulse))
        .unwrap();
    assert!(
        hard.impulse > 1.5 * soft.impulse,
        "{} vs {}",
        hard.impulse,
        soft.impulse
    );
    assert!(peak(hard) > peak(soft), "{} vs {}", peak(hard), peak(soft));
}

/// Same scene and seed, same samples; another seed, another crowd.
#[test]
fn the_soundtrack_is_deterministic() {
    let (a, _, _) = heard();
    let (b, _, _) = listen(None);
    assert!(*a == b);
    let (c, _, _) = listen(Some(99));
    assert!(*a != c);
}

/// A sound on your right is louder and earlier in the right ear, by
/// Woodworth's delay (0.66 ms at the side); in front, both ears alike;
/// and twice as far is half as loud.
#[test]
fn sounds_are_placed_around_your_head() {
    let l = Listener {
        at: DVec3::new(0.0, 1.6, 0.0),
        forward: DVec3::Z,
    };
    let right = l.forward.cross(DVec3::Y);
    let (g, d) = l.place(l.at + right * 2.0);
    assert!(g[1] > 5.0 * g[0].max(1e-3), "{g:?}");
    let itd = (d[0] as f64 - d[1] as f64) / f64::from(RATE);
    assert!((itd - 0.000_656).abs() < 0.000_03, "{itd}");
    let (g, d) = l.place(l.at + l.forward * 2.0);
    assert!((g[0] - g[1]).abs() < 1e-6 && d[0] == d[1]);
    let (g4, _) = l.place(l.at + l.forward * 4.0);
    assert!((g[0] / g4[0] - 2.0).abs() < 1e-3);
}
