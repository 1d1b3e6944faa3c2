// Types of samples.js: the product's sample maps as synthetic-generator recipes.

export interface SampleRecipe {
  /** The `synth` seed. */
  seed: number;
  /** The generator settings over the defaults (`synth(seed, JSON.stringify(config))`). */
  config: Record<string, number>;
  /** The same as a `ksmcmc synth` command line. */
  command: string;
  description: string;
}

export declare const SAMPLES: Readonly<{
  'office-small': SampleRecipe;
  'office-rotated': SampleRecipe;
  furnished: SampleRecipe;
  partial: SampleRecipe;
  'two-corridors': SampleRecipe;
  'building-large': SampleRecipe;
  'two-wings': SampleRecipe;
}>;

/** The `ksmcmc synth` option behind each config field. */
export declare const SYNTH_FLAGS: Readonly<Record<string, string>>;

/** The recipe of a sample; throws an Error naming the samples for an unknown name. */
export function sampleRecipe(name: string): SampleRecipe;
