// One material's BSDF on a backend (BsdfProbe.h).
#include "rill/rt/shaders/BsdfProbe.h"

#include <rill/rill.h>

#include <stdexcept>

#include "rill/rt/kernel/Features.h"
#include "rill/rt/kernel/MaterialTable.h"
#include "rill/rt/shaders/Registry.h"

namespace rt {

using namespace rill;

struct BsdfProbe::Impl {
  std::string backend;
  Scene scene;
  MaterialShaders shaders;
  MaterialTable table;  // the programs read its arrays: it stays where it is (Impl is on the heap)
  Program sample_program, eval_program;

  // The probe's surface (BsdfProbe.h): the local frame, V = wo.
  static Surface surface(const Float3& wo) {
    const Float3 z(0.0f, 0.0f, 1.0f);
    return Surface{Float3(0.0f), z, z, z, wo, Float2(0.0f), Bool(true), Float3(1.0f), Int(0)};
  }
};

BsdfProbe::BsdfProbe(const Material& material, const std::string& backend)
    : d_(std::make_unique<Impl>()) {
  Impl& I = *d_;
  I.backend = backend;
  I.scene.name = "bsdf-probe";
  const int m = I.scene.add_material(material);
  // One usable triangle, so that used_materials marks the material used.
  I.scene.add_triangle(glm::vec3(0.0f), glm::vec3(1.0f, 0.0f, 0.0f), glm::vec3(0.0f, 1.0f, 0.0f),
                       m);
  I.shaders = resolve_shaders(I.scene);
  if (!I.shaders.at(0)->bsdf)
    throw std::invalid_argument("BsdfProbe: shader '" + I.shaders[0]->name + "' of material '" +
                                material.name + "' has no BSDF");
  Features F;
  F.geometry = true;
  I.table.upload(I.scene, F, I.shaders);

  I.sample_program = rill::program("rill_bsdf_probe_sample", [&] {
    Input<Float3> wo("wo");
    Input<Float3> u("u");
    Output<Float3> wi("wi");
    Output<Float3> weight("weight");
    Output<Float> pdf("pdf");
    Output<Int> delta("delta");
    const Surface s = Impl::surface(wo);
    const BsdfSample b = I.table.bsdf_sample(s, u);
    wi = b.wi;
    weight = b.weight;
    pdf = b.pdf;
    delta = select(b.delta, Int(1), Int(0));
  });
  I.eval_program = rill::program("rill_bsdf_probe_eval", [&] {
    Input<Float3> wo("wo");
    Input<Float3> wi("wi");
    Output<Float3> eval("eval");
    Output<Float> pdf("pdf");
    const Surface s = Impl::surface(wo);
    eval = I.table.bsdf_eval(s, wi);
    pdf = I.table.bsdf_pdf(s, wi);
  });
}

BsdfProbe::~BsdfProbe() = default;

const std::string& BsdfProbe::backend() const {
  return d_->backend;
}

std::vector<ProbeSample> BsdfProbe::sample(const std::vector<glm::vec3>& wo,
                                           const std::vector<glm::vec3>& u) {
  if (wo.size() != u.size())
    throw std::invalid_argument("BsdfProbe::sample: wo and u differ in size");
  std::vector<ProbeSample> out(wo.size());
  if (wo.empty()) return out;
  const auto n = static_cast<int64_t>(wo.size());
  Kernel k = compile(d_->sample_program, d_->backend);
  Stream<Float3> wo_s(wo), u_s(u), wi_s(n), weight_s(n);
  Stream<Float> pdf_s(n);
  Stream<Int> delta_s(n);
  k.inputs(wo_s, u_s).outputs(wi_s, weight_s, pdf_s, delta_s);
  k.execute();
  const std::vector<glm::vec3> wi = wi_s.download(), weight = weight_s.download();
  const std::vector<float> pdf = pdf_s.download();
  const std::vector<int32_t> delta = delta_s.download();
  for (size_t i = 0; i < out.size(); ++i) out[i] = {wi[i], weight[i], pdf[i], delta[i] != 0};
  return out;
}

std::vector<ProbeSample> BsdfProbe::sample(const glm::vec3& wo, const std::vector<glm::vec3>& u) {
  return sample(std::vector<glm::vec3>(u.size(), wo), u);
}

std::vector<ProbeEval> BsdfProbe::eval(const std::vector<glm::vec3>& wo,
                                       const std::vector<glm::vec3>& wi) {
  if (wo.size() != wi.size())
    throw std::invalid_argument("BsdfProbe::eval: wo and wi differ in size");
  std::vector<ProbeEval> out(wo.size());
  if (wo.empty()) return out;
  const auto n = static_cast<int64_t>(wo.size());
  Kernel k = compile(d_->eval_program, d_->backend);
  Stream<Float3> wo_s(wo), wi_s(wi), eval_s(n);
  Stream<Float> pdf_s(n);
  k.inputs(wo_s, wi_s).outputs(eval_s, pdf_s);
  k.execute();
  const std::vector<glm::vec3> e = eval_s.download();
  const std::vector<float> pdf = pdf_s.download();
  for (size_t i = 0; i < out.size(); ++i) out[i] = {e[i], pdf[i]};
  return out;
}

std::vector<ProbeEval> BsdfProbe::eval(const glm::vec3& wo, const std::vector<glm::vec3>& wi) {
  return eval(std::vector<glm::vec3>(wi.size(), wo), wi);
}

}  // namespace rt
