#include "lang/convert/foreign_vocabulary.h"

namespace ontogen::convert {

namespace {

constexpr Predefined kPredefined[] = {
    // Both tools' '@' modules.
    {"@O", "sphere", Fate::Translate, false},
    {"@o", "disc", Fate::Translate, false},
    {"@v", "$", Fate::Translate, false},
    {"@M", "MoveTo", Fate::Inert, false},
    {"@R", "SetHead", Fate::Inert, false},
    {"@L", "Label", Fate::Inert, false},
    {"@B", "Box", Fate::Inert, true},
    {"@b", "Quad", Fate::Inert, false},
    {"@g", "PglShape", Fate::Inert, true},
    {"@h", "RollToHorizontal", Fate::Inert, true},
    {"@Dd", "DivScale", Fate::Inert, true},
    {"@Di", "MultScale", Fate::Inert, true},
    {"@D", "SetScale", Fate::Inert, true},
    {"@Ts", "Elasticity", Fate::Inert, true},
    {"@Tp", "Tropism", Fate::Inert, true},
    {"@2D", "StartScreenProjection", Fate::Inert, true},
    {"@3D", "EndScreenProjection", Fate::Inert, true},
    {"@Gc", "gcbegin", Fate::Translate, true},  // L-Py's StartGC
    // cpfg's generalized cylinders (its blackbox.c): @Gs starts one, @Gc adds a control
    // point (ontogen's F adds them), @Gt and @Gr shape its tangents.
    {"@Gs", "gcbegin", Fate::Translate, false, true},
    {"@Gc", "ContinueSpline", Fate::Inert, false, true},
    {"@Gt", "SplineTangents", Fate::Inert, false, true},
    {"@Gr", "RadiusTangents", Fate::Inert, false, true},
    {"@c", "Circle3D", Fate::Inert, false, true},  // a circle facing the turtle's heading
    {"@Ge", "gcend", Fate::Translate, false},
    // cpfg's other '@' modules (its blackbox.c), none of which ontogen's turtle has:
    // textures, the elasticities of its tropisms, the frame kept against twist, the
    // contour and sides of cylinders, the turtle's scale, bounded circles.
    {"@Tx", "Texture", Fate::Inert, false, true},
    {"@Ti", "IncElasticity", Fate::Inert, false, true},
    {"@Td", "DecElasticity", Fate::Inert, false, true},
    {"@Ts", "SetElasticity", Fate::Inert, false, true},
    {"@Tp", "PreventTwist", Fate::Inert, false, true},
    {"@Tf", "AcceptTwist", Fate::Inert, false, true},
    {"@#", "SetContour", Fate::Inert, false, true},
    {"@!", "CylinderSides", Fate::Inert, false, true},
    {"@Dd", "DivScale", Fate::Inert, false, true},
    {"@Di", "MultScale", Fate::Inert, false, true},
    {"@D", "SetScale", Fate::Inert, false, true},
    {"@bo", "BoundedDisc", Fate::Inert, false, true},
    {"@bc", "BoundedCircle3D", Fate::Inert, false, true},
    // L-Py's names.
    {"Sphere", "sphere", Fate::Translate},
    {"Circle", "disc", Fate::Translate},
    {"StartGC", "gcbegin", Fate::Translate},
    {"EndGC", "gcend", Fate::Translate},
    {"IncColor", "color", Fate::Translate},
    {"SetColor", "color", Fate::Translate},
    {"SetWidth", "!", Fate::Translate},
    {"DecWidth", "!", Fate::Translate},
    {"Left", "+", Fate::Translate},
    {"Right", "-", Fate::Translate},
    {"Up", "^", Fate::Translate},
    {"Down", "&", Fate::Translate},
    {"RollL", "/", Fate::Translate},
    {"RollR", "\\", Fate::Translate},
    {"TurnAround", "|", Fate::Translate},
    {"RollToVert", "$", Fate::Translate},
    {"SB", "[", Fate::Translate},
    {"EB", "]", Fate::Translate},
    {"GetPos", "?P", Fate::Translate},
    {"GetHead", "?H", Fate::Translate},
    {"GetUp", "?U", Fate::Translate},
    {"GetLeft", "?L", Fate::Translate},
    {"GetRight", "", Fate::Refuse},
    {"GetFrame", "", Fate::Refuse},
    {"DecColor", "DecColor", Fate::Inert},
    {"nF", "nF", Fate::Inert},
    {"BP", "BP", Fate::Inert},
    {"EP", "EP", Fate::Inert},
    {"PP", "PP", Fate::Inert},
    {"MoveTo", "MoveTo", Fate::Inert},
    {"MoveRel", "MoveRel", Fate::Inert},
    {"LineTo", "LineTo", Fate::Inert},
    {"OLineTo", "OLineTo", Fate::Inert},
    {"LineRel", "LineRel", Fate::Inert},
    {"OLineRel", "OLineRel", Fate::Inert},
    {"Pinpoint", "Pinpoint", Fate::Inert},
    {"PinpointRel", "PinpointRel", Fate::Inert},
    {"SetHead", "SetHead", Fate::Inert},
    {"EulerAngles", "EulerAngles", Fate::Inert},
    {"iRollL", "iRollL", Fate::Inert},
    {"iRollR", "iRollR", Fate::Inert},
    {"RollToHorizontal", "RollToHorizontal", Fate::Inert},
    {"Box", "Box", Fate::Inert},
    {"Quad", "Quad", Fate::Inert},
    {"Label", "Label", Fate::Inert},
    {"IncWidth", "IncWidth", Fate::Inert},
    {"InterpolateColors", "InterpolateColors", Fate::Inert},
    {"TextureBaseColor", "TextureBaseColor", Fate::Inert},
    {"InterpolateTextureBaseColors", "InterpolateTextureBaseColors", Fate::Inert},
    {"DivScale", "DivScale", Fate::Inert},
    {"MultScale", "MultScale", Fate::Inert},
    {"SetScale", "SetScale", Fate::Inert},
    {"PglShape", "PglShape", Fate::Inert},
    {"Frame", "Frame", Fate::Inert},
    {"Arrow", "Arrow", Fate::Inert},
    {"Elasticity", "Elasticity", Fate::Inert},
    {"Tropism", "Tropism", Fate::Inert},
    {"SetContour", "SetContour", Fate::Inert},
    {"SectionResolution", "SectionResolution", Fate::Inert},
    {"SetGuide", "SetGuide", Fate::Inert},
    {"EndGuide", "EndGuide", Fate::Inert},
    {"Sweep", "Sweep", Fate::Inert},
    {"PositionOnGuide", "PositionOnGuide", Fate::Inert},
    {"TextureScale", "TextureScale", Fate::Inert},
    {"TextureUScale", "TextureUScale", Fate::Inert},
    {"TextureVScale", "TextureVScale", Fate::Inert},
    {"TextureVCoeff", "TextureVCoeff", Fate::Inert},
    {"TextureTranslation", "TextureTranslation", Fate::Inert},
    {"TextureRotation", "TextureRotation", Fate::Inert},
    {"TextureTransformation", "TextureTransformation", Fate::Inert},
    {"LeftReflection", "LeftReflection", Fate::Inert},
    {"UpReflection", "UpReflection", Fate::Inert},
    {"HeadingReflection", "HeadingReflection", Fate::Inert},
    {"StartScreenProjection", "StartScreenProjection", Fate::Inert},
    {"EndScreenProjection", "EndScreenProjection", Fate::Inert},
};

}  // namespace

bool inDialect(const Predefined& p, Dialect dialect) {
  return dialect == Dialect::LPy ? !p.cpfgOnly : !p.lpyOnly;
}

const Predefined* predefined(std::string_view name, Dialect dialect) {
  for (const Predefined& p : kPredefined)
    if (p.name == name && inDialect(p, dialect)) return &p;
  return nullptr;
}

std::span<const Predefined> predefinedModules() {
  return kPredefined;
}

}  // namespace ontogen::convert
