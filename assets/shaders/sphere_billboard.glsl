// The corner of a billboard facing the eye that holds the perspective silhouette of a sphere of
// radius r centred at c (eye space), with a pixel of margin at its distance for the rim's
// antialiasing. corner is (+-1, +-1).
vec3 sphere_billboard(vec3 c, float r, vec2 corner, float px_per_depth) {
  float d2 = dot(c, c);
  float s = r * sqrt(d2 / max(d2 - r * r, 1e-4 * d2)) + sqrt(d2) * px_per_depth;
  vec3 w = normalize(c);
  vec3 up = abs(w.y) > 0.99 ? vec3(1.0, 0.0, 0.0) : vec3(0.0, 1.0, 0.0);
  vec3 u = normalize(cross(up, w));
  vec3 v = cross(w, u);
  return c + (corner.x * u + corner.y * v) * s;
}
