// The product's sample maps as recipes for the synthetic generator.
//
// Every sample in the repository's samples/ folder was made by one `ksmcmc synth` command
// (listed in samples/README.md), and the generator gives the same bytes for the same seed and
// settings on every platform. So the package does not ship the maps: `synth(seed, config)`
// remakes them, byte for byte, in a few milliseconds. A test checks this table against the
// README's commands, and the browser tests check the bytes against the files.

/**
 * Sample name -> the `synth` seed and settings (the fields of the generator's JSON config)
 * that make it, with the command-line form and a description.
 * @type {Readonly<Record<string, {seed: number, config: Record<string, number>, command: string, description: string}>>}
 */
export const SAMPLES = Object.freeze({
  'office-small': {
    seed: 1,
    config: {},
    command: 'ksmcmc synth --seed 1',
    description: 'the defaults: one corridor, offices on both sides, one storage unit, light furniture (400 x 300)',
  },
  'office-rotated': {
    seed: 2,
    config: { rotation_deg: 20 },
    command: 'ksmcmc synth --seed 2 --rotation 20',
    description: 'the same kind of floor rotated by 20 degrees (479 x 419)',
  },
  furnished: {
    seed: 3,
    config: { clutter: 0.1, others: 2 },
    command: 'ksmcmc synth --seed 3 --clutter 0.1 --others 2',
    description: 'furniture on 10 % of the room floor (400 x 300)',
  },
  partial: {
    seed: 4,
    config: { unexplored: 0.4 },
    command: 'ksmcmc synth --seed 4 --unexplored 0.4',
    description: '40 % of the rooms never entered (400 x 300)',
  },
  'two-corridors': {
    seed: 5,
    config: { width: 520, height: 400, corridors: 2, wall_thickness: 2, clutter: 0.02 },
    command: 'ksmcmc synth --seed 5 --width 520 --height 400 --corridors 2 --wall-thickness 2 --clutter 0.02',
    description: 'two parallel corridors joined by a connecting corridor, 2-cell walls (520 x 400)',
  },
  'building-large': {
    seed: 6,
    config: { width: 1217, height: 272, rotation_deg: 20, halls: 2, others: 3, clutter: 0.03, unexplored: 0.1 },
    command:
      'ksmcmc synth --seed 6 --width 1217 --height 272 --rotation 20 --halls 2 --others 3 --clutter 0.03 --unexplored 0.1',
    description: 'a long building with halls at both ends, rotated by 20 degrees (1237 x 672)',
  },
  'two-wings': {
    seed: 7,
    config: { width: 300, height: 220, wing_deg: 30 },
    command: 'ksmcmc synth --seed 7 --width 300 --height 220 --wing 30',
    description: 'two buildings joined by a passage, the second turned by 30 degrees (670 x 341)',
  },
});

/** The `ksmcmc synth` option behind each config field, for turning recipes into commands. */
export const SYNTH_FLAGS = Object.freeze({
  width: '--width',
  height: '--height',
  rotation_deg: '--rotation',
  corridors: '--corridors',
  halls: '--halls',
  others: '--others',
  wall_thickness: '--wall-thickness',
  clutter: '--clutter',
  unexplored: '--unexplored',
  wing_deg: '--wing',
});

/**
 * The recipe of a sample, or an Error naming the samples there are.
 * @param {string} name
 */
export function sampleRecipe(name) {
  const recipe = Object.hasOwn(SAMPLES, name) ? SAMPLES[name] : undefined;
  if (!recipe) {
    throw new Error(`unknown sample ${JSON.stringify(name)}; the samples are ${Object.keys(SAMPLES).join(', ')}`);
  }
  return recipe;
}
