// Mitsuba's shapes (meshes, analytic shapes, groups and instances) to our objects.
#include "io/mitsuba/translator.h"
#include <cmath>
#include <filesystem>
#include "io/mitsuba/shapes.h"

namespace caustica::mitsuba_translation {
namespace fs = std::filesystem;

namespace {
const std::set<std::string> kShapes = {"obj",      "ply",        "serialized", "rectangle", "cube",   "disk",
                                       "sphere",   "cylinder",   "shapegroup", "instance",  "sdfgrid", "linearcurve", "bsplinecurve"};
}  // namespace

void Translator::shape(const XmlObject& o, const glm::dmat4& parent) {
  count_expansion(o);
  if (!kShapes.count(o.type)) {
    unsupported(o, "shape", kShapes, "skipped");
    return;
  }
  Props props(o);
  if (o.type == "instance") {
    const XmlObject* group = nullptr;
    for (const XmlChild& c : o.children) {
      if (c.object->tag == "shape" && c.object->type == "shapegroup") group = c.object;
      else bad_child(o, c);
    }
    if (!group) throw InputError(o.where + ": an instance needs a <ref> to a shapegroup");
    const glm::dmat4 m = props.get("to_world") ? transform(*props.get("to_world")) : glm::dmat4(1.0);
    refuse_unused(o, props);
    for (const XmlChild& c : group->children) {
      if (c.object->tag != "shape") bad_child(*group, c);
      shape(*c.object, parent * m);
    }
    return;
  }
  json& objects = out_.doc["objects"];
  const std::string p = "/objects/" + std::to_string(objects.size());
  note(p, o.where);
  const XmlObject* bsdf_obj = nullptr;
  const XmlObject* area = nullptr;
  std::vector<std::pair<std::string, const XmlObject*>> media;  // ("interior" or "exterior", the medium)
  for (const XmlChild& c : o.children) {
    if (c.object->tag == "bsdf" && !bsdf_obj) bsdf_obj = c.object;
    else if (c.object->tag == "emitter" && !area) area = c.object;
    else if (c.object->tag == "medium" && (c.name == "interior" || c.name == "exterior")) media.emplace_back(c.name, c.object);
    else if (c.object->tag == "subsurface") unsupported(*c.object, "subsurface", {}, "ignored (the shape's BSDF alone renders it)");
    else bad_child(o, c);
  }
  json emission;
  const XmlProperty* weight = nullptr;
  if (area) {
    if (area->type != "area") throw InputError(area->where + ": only an \"area\" emitter can be attached to a shape");
    Props ap(*area);
    const XmlProperty* r = ap.get("radiance");
    emission = r ? color_json(*r, SpectrumUse::Emission) : default_emission();
    if (r) note(p + "/material/emission", r->where);
    weight = ap.get("sampling_weight");
    if (weight) note(p + "/sampling_weight", weight->where);
    refuse_unused(*area, ap);
    bool given = r != nullptr;
    for (const XmlChild& c : area->children) {
      // A texture as the radiance (over the shape's UVs).
      if (c.object->tag != "texture" || c.name != "radiance" || given) {
        throw InputError(c.where + ": an area emitter takes one radiance, a value or a <texture name=\"radiance\">");
      }
      emission = texture(*c.object, p + "/material/emission");
      given = true;
      note(p + "/material/emission", c.where);
    }
  }
  std::string material;
  if (bsdf_obj) {
    material = material_name(*bsdf_obj, area ? &emission : nullptr);
  } else {
    // Mitsuba's default: a diffuse BSDF of reflectance 0.5.
    const std::string name = "default diffuse" + std::string(area ? " + emitter " + std::to_string(++anonymous_) : "");
    json m = default_bsdf();
    if (area) m["emission"] = emission;
    out_.doc["materials"][name] = m;
    note("/materials/" + name, area ? area->where : o.where);
    material = name;
  }
  json obj = {{"name", o.id.empty() ? o.type : o.id}, {"material", material}};
  for (const auto& [side, m] : media) {
    const std::string name = medium(*m);
    if (name.empty()) continue;
    obj[side] = name;
    note(p + "/" + side, m->where);
  }
  note(p + "/material", bsdf_obj ? bsdf_obj->where : o.where);
  if (o.type == "obj" && !bsdf_obj && !area) {
    // An OBJ with an .mtl and no BSDF in the scene keeps its own materials (Mitsuba would
    // give it the default diffuse, which faces without a material still get).
    obj.erase("material");
    obj["default_material"] = material;
    note(p + "/default_material", o.where);
  }
  const glm::dmat4 m = parent * (props.get("to_world") ? transform(*props.get("to_world")) : glm::dmat4(1.0));
  if (const XmlProperty* f = props.get("flip_normals")) {
    obj["flip_normal"] = boolean(*f);
    note(p + "/flip_normal", f->where);
  }
  if (o.type == "sphere") {
    glm::dvec3 c(0.0);
    double r = 1.0;
    if (const XmlProperty* cp = props.get("center")) c = point(*cp);
    if (const XmlProperty* rp = props.get("radius")) {
      r = number(*rp);
      note(p + "/radius", rp->where);
    }
    // The transform must keep it a sphere: a uniform scale, rotation and translation.
    const glm::dmat3 l(m);
    const double s = glm::length(l[0]);
    const glm::dmat3 check = glm::transpose(l) * l;
    for (int a = 0; a < 3; ++a) {
      for (int b = 0; b < 3; ++b) {
        if (std::abs(check[a][b] - (a == b ? s * s : 0.0)) > 1e-4 * s * s) {
          throw InputError((o.prop("to_world") ? o.prop("to_world")->where : o.where) +
                           ": a sphere's to_world must be a uniform scale, rotation and translation");
        }
      }
    }
    obj["type"] = "sphere";
    obj["center"] = vec(glm::dvec3(m * glm::dvec4(c, 1.0)));
    obj["radius"] = r * s;
  } else if (o.type == "sdfgrid" || o.type == "linearcurve" || o.type == "bsplinecurve") {
    // A grid over the unit cube, or a curve file's control points, under to_world (and the
    // instances' transforms above it).
    obj["type"] = o.type;
    const XmlProperty* f = props.get("filename");
    if (!f) throw InputError(o.where + ": missing <string name=\"filename\">");
    obj["file"] = resolve(o, *f);
    note(p + "/file", f->where);
    if (const XmlProperty* n = o.type == "sdfgrid" ? props.get("normals") : nullptr) {
      obj["normals"] = string(*n);
      note(p + "/normals", n->where);
    }
    if (m != glm::dmat4(1.0)) {
      obj["to_world"] = rows(m);
      if (const XmlProperty* t = o.prop("to_world")) note(p + "/to_world", t->where);
    }
  } else {
    obj["type"] = "mesh";
    glm::dmat4 local(1.0);
    if (o.type == "obj" || o.type == "ply" || o.type == "serialized") {
      const XmlProperty* f = props.get("filename");
      if (!f) throw InputError(o.where + ": missing <string name=\"filename\">");
      obj["file"] = resolve(o, *f);
      note(p + "/file", f->where);
      if (const XmlProperty* si = props.get("shape_index")) {
        if (o.type != "serialized") throw InputError(si->where + ": shape_index applies to serialized shapes only");
        obj["shape_index"] = integer(*si);
        note(p + "/shape_index", si->where);
      }
      if (const XmlProperty* ft = props.get("flip_tex_coords")) {
        // Mitsuba flips OBJ's v by default (as we do) and not PLY's or serialized's.
        if (boolean(*ft) != (o.type == "obj")) unsupported_property(*ft, "ignored");
      }
      props.ignore({"collapse"});
    } else if (o.type == "rectangle") {
      obj.update(rectangle_mesh());
    } else if (o.type == "cube") {
      obj.update(cube_mesh());
    } else if (o.type == "disk") {
      obj.update(disk_mesh(kRoundSegments));
    } else if (o.type == "cylinder") {
      glm::dvec3 p0(0.0), p1(0, 0, 1);
      double radius = 1.0;
      if (const XmlProperty* a = props.get("p0")) p0 = point(*a);
      if (const XmlProperty* b = props.get("p1")) p1 = point(*b);
      if (const XmlProperty* r = props.get("radius")) radius = number(*r);
      const glm::dvec3 axis = p1 - p0;
      const double len = glm::length(axis);
      if (!(len > 0.0) || !(radius > 0.0)) throw InputError(o.where + ": the cylinder has no extent (p0 = p1 or radius <= 0)");
      // Object to world: translate(p0) * frame(axis) * scale(r, r, len).
      const glm::dvec3 w = axis / len;
      const glm::dvec3 u = glm::normalize(std::abs(w.x) > 0.9 ? glm::cross(w, glm::dvec3(0, 1, 0)) : glm::cross(w, glm::dvec3(1, 0, 0)));
      const glm::dvec3 v = glm::cross(w, u);
      local[0] = glm::dvec4(u * radius, 0.0);
      local[1] = glm::dvec4(v * radius, 0.0);
      local[2] = glm::dvec4(w * len, 0.0);
      local[3] = glm::dvec4(p0, 1.0);
      obj.update(cylinder_mesh(kRoundSegments));
    } else {
      throw InputError(o.where + ": a shapegroup is drawn through an <shape type=\"instance\">");
    }
    if (const XmlProperty* fn = props.get("face_normals")) {
      obj["face_normals"] = boolean(*fn);
      note(p + "/face_normals", fn->where);
    }
    const glm::dmat4 full = m * local;
    // Mitsuba's rectangle, disk and cylinder carry their normal through the inverse transpose,
    // which a mirroring transform does not flip, while the triangles' winding does.
    if ((o.type == "rectangle" || o.type == "disk" || o.type == "cylinder") && glm::determinant(glm::dmat3(full)) < 0.0) {
      obj["flip_normal"] = !(obj.contains("flip_normal") && obj["flip_normal"].get<bool>());
    }
    // Mitsuba computes smooth vertex normals for a mesh file without them (unless face_normals);
    // 0.6's maxSmoothAngle rebuilds them all, keeping creases sharper than the angle.
    const bool mesh_file = o.type == "obj" || o.type == "ply" || o.type == "serialized";
    if (const XmlProperty* a = mesh_file ? props.get("max_smooth_angle") : nullptr) {
      obj["max_smooth_angle"] = number(*a);
      note(p + "/max_smooth_angle", a->where);
    } else if (mesh_file && !(obj.contains("face_normals") && obj["face_normals"].get<bool>())) {
      obj["smooth_normals"] = true;
    }
    if (full != glm::dmat4(1.0)) {
      obj["to_world"] = rows(full);
      if (const XmlProperty* t = o.prop("to_world")) note(p + "/to_world", t->where);
    }
  }
  if (weight) obj["sampling_weight"] = number(*weight);
  refuse_unused(o, props);
  objects.push_back(obj);
}

}  // namespace caustica::mitsuba_translation
