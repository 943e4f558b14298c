// The classic material of the thesis and of MTL files: a diffuse colour, a Phong highlight,
// mirror reflection and refraction. It is how MTL files (Kd, Ks, Ns, Ni, d, illum), JSON
// materials that name no shader (docs/scene-format.md) and the built-in scenes describe a
// surface, and it maps onto the built-in shaders' parameters of the same names: a material
// of the phong shader, or of glass where it transmits light.
#pragma once

#include <string>

#include "rill/rt/scene/Scene.h"

namespace rt {

struct ClassicMaterial {
  glm::vec3 diffuse{0.8f};   // Kd
  glm::vec3 specular{0.0f};  // Ks (the Phong highlight)
  float shininess = 32.0f;   // Ns (the Phong exponent)
  float reflect = 0.0f;      // mirror reflection, the coefficient r of the thesis's eq. 5.1
  float transmit = 0.0f;     // the share refracted (glass); split by Fresnel (Schlick)
  float ior = 1.5f;          // index of refraction (Ni)

  // The material: shader glass when transmit > 0, else phong; each parameter the shader
  // declares set to the value here (phong has no transmit or ior).
  Material material(const std::string& name) const;
  // What is wrong with the values ("reflect and transmit must be >= 0 with reflect +
  // transmit <= 1"), or empty.
  std::string problem() const;
};

// The keys of a JSON material without "shader" (the fields above, by their names), and
// whether a key is one: diffuse and specular are colours (a texture too), the others
// numbers.
inline constexpr const char* kClassicKeys[] = {"diffuse", "specular", "shininess",
                                               "reflect", "transmit", "ior"};
bool is_classic_key(const std::string& key);
bool is_classic_color(const std::string& key);
// Sets the field named key (one of kClassicKeys) to v (a number, or a colour for a colour
// key).
void set_classic(ClassicMaterial& m, const std::string& key, const ParamValue& v);

}  // namespace rt
