// The sphere ray-cast through its billboard: coverage from the ray's miss distance one pixel
// wide (antialiasing without multisampling), Lambert plus a small specular term, and the true
// depth of the hit, so that spheres cut each other as solids do.
in vec3 vpos;
flat in vec3 centre;
flat in float radius;
flat in vec4 col;
uniform mat4 proj;
uniform vec3 light;  // unit, eye space
uniform float px_per_depth;
out vec4 frag;
void main() {
  vec3 dir = normalize(vpos);
  float b = dot(dir, centre);
  vec3 q = centre - b * dir;  // from the ray's closest point to the centre: stable in float
  float miss = length(q);
  float cover = clamp((radius - miss) / (b * px_per_depth) + 0.5, 0.0, 1.0);
  if (cover <= 0.0 || b <= 0.0) discard;
  float t = b - sqrt(max(radius * radius - miss * miss, 0.0));
  vec3 p = dir * t;
  vec3 n = (p - centre) / radius;
  float diffuse = max(dot(n, light), 0.0);
  float spec = pow(max(dot(n, normalize(light - dir)), 0.0), 40.0);
  frag = vec4(col.rgb * (0.3 + 0.7 * diffuse) + vec3(0.25 * spec), cover);
  vec4 clip = proj * vec4(p, 1.0);
  gl_FragDepth = 0.5 * clip.z / clip.w + 0.5;
}
