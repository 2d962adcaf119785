// Leaf coverage of the crown's silhouette hull (see tools/viewer/README.md for the definition).
// Pure functions on pixel masks, shared by the browser page and the node tests.
//
// A mask is a Uint8Array of width*height entries, 1 where the pass covered the pixel, row 0 at the
// top of the image (the page flips the GL read-back before calling these).

// Andrew's monotone chain; points are [x, y] pairs. Returns the hull counter-clockwise without
// repeating the first point. Collinear points are dropped.
export function convexHull(points) {
  const pts = points.slice().sort((a, b) => a[0] - b[0] || a[1] - b[1]);
  if (pts.length <= 2) return pts;
  const cross = (o, a, b) => (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0]);
  const lower = [];
  for (const p of pts) {
    while (lower.length >= 2 && cross(lower[lower.length - 2], lower[lower.length - 1], p) <= 0) lower.pop();
    lower.push(p);
  }
  const upper = [];
  for (let i = pts.length - 1; i >= 0; i--) {
    const p = pts[i];
    while (upper.length >= 2 && cross(upper[upper.length - 2], upper[upper.length - 1], p) <= 0) upper.pop();
    upper.push(p);
  }
  lower.pop();
  upper.pop();
  return lower.concat(upper);
}

// Pixels whose centre lies inside or on the polygon (pixel (x, y) has its centre at (x, y) here,
// the same coordinates the hull points use). Returns a mask.
export function rasterizeHull(hull, width, height) {
  const mask = new Uint8Array(width * height);
  if (hull.length === 0) return mask;
  const eps = 1e-7;
  let minY = Infinity;
  let maxY = -Infinity;
  for (const [, y] of hull) {
    minY = Math.min(minY, y);
    maxY = Math.max(maxY, y);
  }
  for (let y = Math.max(0, Math.ceil(minY - eps)); y <= Math.min(height - 1, Math.floor(maxY + eps)); y++) {
    let lo = Infinity;
    let hi = -Infinity;
    for (let i = 0; i < hull.length; i++) {
      const a = hull[i];
      const b = hull[(i + 1) % hull.length];
      const y0 = Math.min(a[1], b[1]);
      const y1 = Math.max(a[1], b[1]);
      if (y < y0 - eps || y > y1 + eps) continue;
      if (Math.abs(b[1] - a[1]) < eps) {
        lo = Math.min(lo, a[0], b[0]);
        hi = Math.max(hi, a[0], b[0]);
      } else {
        const x = a[0] + ((y - a[1]) * (b[0] - a[0])) / (b[1] - a[1]);
        lo = Math.min(lo, x);
        hi = Math.max(hi, x);
      }
    }
    if (hi < lo) continue;
    const x0 = Math.max(0, Math.ceil(lo - eps));
    const x1 = Math.min(width - 1, Math.floor(hi + eps));
    mask.fill(1, y * width + x0, y * width + x1 + 1);
  }
  return mask;
}

function count(mask) {
  let n = 0;
  for (let i = 0; i < mask.length; i++) n += mask[i];
  return n;
}

// whole, leaf, bark: masks of the three passes. Returns the numbers and the hull mask.
//   crown_base_row: lowest image row (largest y) holding a leaf pixel; -1 when there is none.
//   hull: convex hull of the whole-tree silhouette pixels in rows 0..crown_base_row.
//   coverage: leaf pixels inside the hull / hull pixels.
// With no leaf pixel at all the crown is the whole silhouette and coverage is 0.
export function computeCoverage({ width, height, whole, leaf, bark }) {
  let crownBase = -1;
  for (let y = height - 1; y >= 0 && crownBase < 0; y--) {
    for (let x = 0; x < width; x++) {
      if (leaf[y * width + x]) {
        crownBase = y;
        break;
      }
    }
  }
  const lastRow = crownBase >= 0 ? crownBase : height - 1;
  const points = [];
  for (let y = 0; y <= lastRow; y++) {
    let left = -1;
    let right = -1;
    for (let x = 0; x < width; x++) {
      if (whole[y * width + x]) {
        if (left < 0) left = x;
        right = x;
      }
    }
    if (left >= 0) {
      points.push([left, y]);
      if (right !== left) points.push([right, y]);
    }
  }
  const hull = convexHull(points);
  const hullMask = rasterizeHull(hull, width, height);
  let hullPx = 0;
  let leafIn = 0;
  for (let i = 0; i < hullMask.length; i++) {
    if (hullMask[i]) {
      hullPx++;
      if (leaf[i]) leafIn++;
    }
  }
  return {
    coverage: hullPx > 0 && crownBase >= 0 ? leafIn / hullPx : 0,
    hull_px: hullPx,
    leaf_px: leafIn,
    leaf_px_total: count(leaf),
    bark_px: count(bark),
    silhouette_px: count(whole),
    crown_base_row: crownBase,
    hull_vertices: hull.length,
    hullMask,
  };
}

// RGBA picture of the measurement: hull pixels light grey, leaf pixels inside the hull green,
// bark-only pixels brown, silhouette outside the hull (the trunk below the crown base) dark grey,
// everything else white; a red line marks the crown base row.
export function overlayRGBA({ width, height, whole, leaf, bark }, hullMask, crownBase) {
  const out = new Uint8ClampedArray(width * height * 4);
  for (let i = 0; i < width * height; i++) {
    let c = [255, 255, 255];
    if (hullMask[i]) c = [215, 215, 215];
    if (whole[i] && !hullMask[i]) c = [90, 90, 90];
    if (bark[i] && !leaf[i]) c = [140, 95, 55];
    if (leaf[i] && hullMask[i]) c = [60, 160, 60];
    if (leaf[i] && !hullMask[i]) c = [30, 90, 30];
    out[i * 4] = c[0];
    out[i * 4 + 1] = c[1];
    out[i * 4 + 2] = c[2];
    out[i * 4 + 3] = 255;
  }
  if (crownBase >= 0) {
    for (let x = 0; x < width; x++) {
      const i = (crownBase * width + x) * 4;
      out[i] = 220;
      out[i + 1] = 30;
      out[i + 2] = 30;
    }
  }
  return out;
}
