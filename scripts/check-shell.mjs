#!/usr/bin/env node
// The demo's seven pages share one shell: the start of the head (charset, viewport,
// description, "Page · ksmcmc" title, icon, style sheet), the skip link, the header with the
// brand and the pages' nav, and the message box. No build step puts the pages together: each
// is plain HTML that paints at once, offline and without JavaScript (the nav is there for
// keyboard users and screen readers before any script runs), so each holds a copy of the
// shell, and this script keeps the copies from drifting apart. index.html's shell is the
// reference; the others must match it except for which nav link is the current page
// (aria-current) and what is page-specific by nature (the description, the title, the skip
// link's words, and a tagline listed in TAGLINES).
//
// Usage: node scripts/check-shell.mjs [--write] [www-dir]
//   Lists every difference and exits 1 if there is one. With --write it first copies
//   index.html's header and message box into the other pages (so that a change to the shell is
//   made once, in index.html). tests/e2e/unit.test.mjs runs the check.

import { readFileSync, writeFileSync } from 'node:fs';
import { dirname, join, resolve } from 'node:path';
import { fileURLToPath, pathToFileURL } from 'node:url';

/** The pages, in the order of the nav. */
export const PAGES = ['index.html', 'mapper.html', 'explore.html', 'embed.html', 'rules.html', 'prior.html', 'tabletop.html'];
/** The page whose shell the others copy. */
export const REFERENCE = 'index.html';
/** Pages whose header says what they are about in their own words (the others: the reference's tagline). */
export const TAGLINES = { 'tabletop.html': 'scene graphs from noisy 6D poses' };

const HEADER = /<header class="top">[\s\S]*?<\/header>/;
const MESSAGE = /<div id="message"[^>]*>[\s\S]*?<\/div>/;
const TAGLINE = /(<span class="tagline">)([^<]*)(<\/span>)/;
const CURRENT = / aria-current="page"/g;
const HEAD_LINES = 6;

/** The pieces of a page's shell, with what may differ from page to page taken out. */
function pieces(page, html) {
  const problems = [];
  const header = HEADER.exec(html)?.[0];
  const message = MESSAGE.exec(html)?.[0];
  const head = /<head>([\s\S]*?)<\/head>/.exec(html)?.[1];
  if (!header) problems.push(`${page}: no <header class="top">`);
  if (!message) problems.push(`${page}: no message box (<div id="message" …>)`);
  if (!head) problems.push(`${page}: no <head>`);
  if (problems.length) return { problems };

  // The current page: one nav link, to the page itself; the title is its label.
  const current = [...header.matchAll(/<a href="([^"]+)" aria-current="page">([^<]*)<\/a>/g)];
  let label = null;
  if (current.length !== 1 || current[0][1] !== page) {
    problems.push(`${page}: the nav must mark its own link, and only it, aria-current="page" (marked: ${current.map((m) => m[1]).join(', ') || 'none'})`);
  } else {
    label = current[0][2];
  }
  const tagline = TAGLINE.exec(header)?.[2];
  const wantTagline = TAGLINES[page];
  if (wantTagline !== undefined && tagline !== wantTagline) {
    problems.push(`${page}: its tagline is "${tagline}", not "${wantTagline}" (TAGLINES in scripts/check-shell.mjs)`);
  }

  const headLines = head.split('\n').map((l) => l.trim()).filter(Boolean).slice(0, HEAD_LINES);
  const title = /^<title>(.*) · ksmcmc<\/title>$/.exec(headLines[3] ?? '')?.[1];
  if (label !== null && title !== label) problems.push(`${page}: the title says "${title}", the nav "${label}" (want <title>${label} · ksmcmc</title>)`);
  const headShape = headLines
    .map((l) => l.replace(/^(<meta name="description" content=")[^"]+(">)$/, '$1…$2').replace(/^<title>.* · ksmcmc<\/title>$/, '<title>… · ksmcmc</title>'))
    .join('\n');

  // The skip link comes first in the body, to the page's main.
  const start = /<body[^>]*>\s*(<[^>]*>(?:[^<]*<\/a>)?)/.exec(html)?.[1] ?? '';
  if (!/^<a class="skip" href="#main">[^<]+<\/a>$/.test(start)) problems.push(`${page}: the body must start with <a class="skip" href="#main">…</a> (it starts with ${start.slice(0, 60) || 'nothing'})`);
  if (!/<main id="main"[^>]*\btabindex="-1"/.test(html)) problems.push(`${page}: no <main id="main" … tabindex="-1"> for the skip link`);

  const doctype = html.startsWith('<!doctype html>\n<html lang="en"');
  if (!doctype) problems.push(`${page}: must start with <!doctype html> and <html lang="en" …>`);

  return {
    problems,
    header: header.replace(CURRENT, '').replace(TAGLINE, wantTagline === undefined ? '$1$2$3' : '$1…$3'),
    tagline,
    message,
    headShape,
  };
}

/** The first line where `a` and `b` differ, for a message. */
function firstDifference(a, b) {
  const la = a.split('\n');
  const lb = b.split('\n');
  for (let i = 0; i < Math.max(la.length, lb.length); i++) {
    if (la[i] !== lb[i]) return `line ${i + 1}: ${JSON.stringify(lb[i] ?? '(none)')} where ${REFERENCE} has ${JSON.stringify(la[i] ?? '(none)')}`;
  }
  return 'they differ';
}

/** Every way the pages' shells in `www` differ from index.html's: [] when they are one. */
export function checkShells(www) {
  const read = (page) => readFileSync(join(www, page), 'utf8');
  const ref = pieces(REFERENCE, read(REFERENCE));
  const problems = [...ref.problems];
  if (ref.problems.length) return problems;
  const navPages = [...ref.header.matchAll(/<li><a href="([^"]+)"/g)].map((m) => m[1]);
  if (navPages.join() !== PAGES.join()) problems.push(`${REFERENCE}: the nav lists ${navPages.join(', ')}; PAGES in scripts/check-shell.mjs lists ${PAGES.join(', ')}`);
  for (const page of PAGES.filter((p) => p !== REFERENCE)) {
    const p = pieces(page, read(page));
    problems.push(...p.problems);
    if (p.problems.length && !p.header) continue;
    // A page with a tagline of its own is compared with the reference's tagline taken out.
    const refHeader = TAGLINES[page] === undefined ? ref.header : ref.header.replace(TAGLINE, '$1…$3');
    if (p.header !== refHeader) problems.push(`${page}: the header differs from ${REFERENCE}'s, ${firstDifference(refHeader, p.header)}`);
    if (p.message !== ref.message) problems.push(`${page}: the message box differs from ${REFERENCE}'s, ${firstDifference(ref.message, p.message)}`);
    if (p.headShape !== ref.headShape) problems.push(`${page}: the start of the head differs from ${REFERENCE}'s, ${firstDifference(ref.headShape, p.headShape)}`);
  }
  return problems;
}

/**
 * Copies index.html's header (with the page's own link current and its tagline, if it has one
 * of its own) and message box into the other pages. Returns the pages changed.
 */
export function writeShells(www) {
  const refHtml = readFileSync(join(www, REFERENCE), 'utf8');
  const header = HEADER.exec(refHtml)[0].replace(CURRENT, '');
  const message = MESSAGE.exec(refHtml)[0];
  const changed = [];
  for (const page of PAGES.filter((p) => p !== REFERENCE)) {
    const path = join(www, page);
    const html = readFileSync(path, 'utf8');
    let own = header.replace(`<a href="${page}">`, `<a href="${page}" aria-current="page">`);
    if (TAGLINES[page] !== undefined) own = own.replace(TAGLINE, (_, a, _t, b) => `${a}${TAGLINES[page]}${b}`);
    const out = html.replace(HEADER, () => own).replace(MESSAGE, () => message);
    if (out !== html) {
      writeFileSync(path, out);
      changed.push(page);
    }
  }
  return changed;
}

if (process.argv[1] && import.meta.url === pathToFileURL(resolve(process.argv[1])).href) {
  const args = process.argv.slice(2);
  const write = args.includes('--write');
  const www = resolve(args.find((a) => !a.startsWith('--')) ?? join(dirname(fileURLToPath(import.meta.url)), '../www'));
  if (write) {
    const changed = writeShells(www);
    console.log(changed.length ? `wrote the shell into ${changed.join(', ')}` : 'every page had the shell already');
  }
  const problems = checkShells(www);
  for (const p of problems) console.error(p);
  if (problems.length) process.exit(1);
  console.log(`the ${PAGES.length} pages share one shell`);
}
