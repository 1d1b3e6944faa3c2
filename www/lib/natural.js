// Sorting names as people read them.

/** Compares two names with their digit runs by value: U2 before U10. */
export function naturalCompare(a, b) {
  return String(a).localeCompare(String(b), 'en', { numeric: true });
}
