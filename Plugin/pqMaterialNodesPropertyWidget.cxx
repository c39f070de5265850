#include "pqMaterialNodesPropertyWidget.h"

#include "pqDoubleLineEdit.h"
#include "pqMaterialParameterSpinBox.h"
#include "mmvNumberText.h"
#include "pqPropertiesPanel.h"

#include "vtkCommand.h"
#include "vtkEventQtSlotConnect.h"
#include "vtkLogger.h"
#include "vtkMaterialLibrary.h"
#include "vtkMaterialTransferFunction.h"
#include "vtkMultiMaterialParameters.h"
#include "vtkNew.h"
#include "vtkPVArrayInformation.h"
#include "vtkPVDataInformation.h"
#include "vtkPVLogger.h"
#include "vtkSMProperty.h"
#include "vtkSMPropertyHelper.h"
#include "vtkSMProxy.h"
#include "vtkSMRepresentationProxy.h"
#include "vtkSMStringVectorProperty.h"
#include "vtkWeakPointer.h"

#include <QComboBox>
#include <QDoubleSpinBox>
#include <QGridLayout>
#include <QHBoxLayout>
#include <QIcon>
#include <QImage>
#include <QKeyEvent>
#include <QLabel>
#include <QMouseEvent>
#include <QPainter>
#include <QPainterPath>
#include <QPixmap>
#include <QResizeEvent>
#include <QStringList>
#include <QStyle>
#include <QTextStream>
#include <QToolButton>
#include <QVBoxLayout>

#include <algorithm>
#include <array>
#include <cmath>
#include <utility>
#include <vector>

namespace
{
constexpr int Stride = vtkMaterialTransferFunction::NodeStride; // value + 9 parameters
constexpr int ParameterCount = mmv::MaterialParameterCount;
static_assert(Stride == ParameterCount + 1, "MaterialNodes layout: value + parameters");

using Node = std::array<double, Stride>;

QString parameterLabel(int p)
{
  QString key = QString::fromLatin1(mmv::MaterialParameterTable[p].Key);
  key[0] = key[0].toUpper();
  return key;
}

// The editor's row label. ParaView's Volume representation shows its own
// "Specular" (Lighting group) in the same panel, so ours says whose it is.
QString editorLabel(int p)
{
  return p == mmv::Specular ? pqMaterialNodesPropertyWidget::tr("Material Specular")
                            : parameterLabel(p);
}

// A preset's swatch: a grey sphere shaded with the preset's ambient,
// diffuse, specular and shininess (Blinn-Phong, light from the upper left).
// Grey, because a preset sets the material, never the colour: that comes
// from the colour map (issue 12: coloured swatches promised colours).
QPixmap presetSwatch(const double parameters[ParameterCount], int size)
{
  QImage image(size, size, QImage::Format_ARGB32);
  image.fill(Qt::transparent);
  const double light[3] = { -0.48, -0.55, 0.68 }; // y down, towards the viewer
  const double norm = std::sqrt(light[0] * light[0] + light[1] * light[1] + light[2] * light[2]);
  const double l[3] = { light[0] / norm, light[1] / norm, light[2] / norm };
  double h[3] = { l[0], l[1], l[2] + 1.0 };
  const double hn = std::sqrt(h[0] * h[0] + h[1] * h[1] + h[2] * h[2]);
  const double albedo = 0.75;
  for (int y = 0; y < size; ++y)
  {
    for (int x = 0; x < size; ++x)
    {
      const double nx = (x + 0.5) / size * 2.0 - 1.0;
      const double ny = (y + 0.5) / size * 2.0 - 1.0;
      const double r2 = nx * nx + ny * ny;
      if (r2 > 1.0)
      {
        continue;
      }
      const double nz = std::sqrt(1.0 - r2);
      const double ndotl = std::max(0.0, nx * l[0] + ny * l[1] + nz * l[2]);
      const double ndoth = std::max(0.0, (nx * h[0] + ny * h[1] + nz * h[2]) / hn);
      const double shade = albedo * (parameters[mmv::Ambient] + parameters[mmv::Diffuse] * ndotl) +
        (ndotl > 0.0 ? parameters[mmv::Specular] * std::pow(ndoth, parameters[mmv::Shininess])
                     : 0.0);
      const int grey = static_cast<int>(std::round(255.0 * std::min(1.0, shade)));
      image.setPixel(x, y, qRgba(grey, grey, grey, 255));
    }
  }
  return QPixmap::fromImage(image);
}

// What a preset sets, for its tooltip.
QString presetDescription(const char* name, const double parameters[ParameterCount])
{
  QStringList values;
  for (int p = 0; p < ParameterCount; ++p)
  {
    values << QStringLiteral("%1 %2").arg(QString::fromLatin1(mmv::MaterialParameterTable[p].Key))
                .arg(parameters[p]);
  }
  return pqMaterialNodesPropertyWidget::tr(
    "%1 sets the material only (%2); colour and opacity stay those of the colour map.")
    .arg(QString::fromUtf8(name))
    .arg(values.join(", "));
}

bool validRange(const double r[2])
{
  return std::isfinite(r[0]) && std::isfinite(r[1]) && r[1] > r[0];
}
}

//-----------------------------------------------------------------------------
// The node track: nodes as handles along the data range, over the opacity
// curve and the curve of one material parameter. No Q_OBJECT: it calls back
// into the owning widget, which holds all state.
class pqMaterialNodesTrack : public QWidget
{
public:
  explicit pqMaterialNodesTrack(pqMaterialNodesPropertyWidget* owner)
    : QWidget(owner)
    , Owner(owner)
  {
    this->setObjectName("Track");
    this->setFocusPolicy(Qt::StrongFocus);
    this->setMouseTracking(false);
    this->setSizePolicy(QSizePolicy::Expanding, QSizePolicy::Fixed);
    this->setToolTip(pqMaterialNodesPropertyWidget::tr(
      "Click to add a material node, drag a node to move it, Delete removes the selected node."));
  }

  QSize sizeHint() const override { return QSize(240, 84); }
  QSize minimumSizeHint() const override { return QSize(120, 84); }

  // Geometry: the plot (opacity and parameter curves) on top, the handle
  // strip below it, the range labels at the bottom.
  static constexpr int Radius = 5;
  QRectF plotRect() const
  {
    const int text = this->fontMetrics().height();
    return QRectF(Radius + 3, 3, this->width() - 2 * (Radius + 3),
      this->height() - 3 - text - 2 * Radius - 6);
  }
  double handleY() const { return this->plotRect().bottom() + Radius + 3; }

  double toX(double value, const double range[2]) const
  {
    const QRectF r = this->plotRect();
    return r.left() + (value - range[0]) / (range[1] - range[0]) * r.width();
  }
  double toValue(double x, const double range[2]) const
  {
    const QRectF r = this->plotRect();
    return range[0] + (x - r.left()) / r.width() * (range[1] - range[0]);
  }

  // Nearest node within grabbing distance of x, -1 if none.
  int nodeAt(double x) const;

protected:
  void paintEvent(QPaintEvent*) override;
  void mousePressEvent(QMouseEvent* event) override;
  void mouseMoveEvent(QMouseEvent* event) override;
  void mouseReleaseEvent(QMouseEvent* event) override;
  void keyPressEvent(QKeyEvent* event) override;

private:
  pqMaterialNodesPropertyWidget* Owner;
  int Dragging = -1;
  bool Moved = false;
  bool Pending = false; // node added by this press, not yet committed
  double DragRange[2] = { 0, 1 };
};

//-----------------------------------------------------------------------------
class pqMaterialNodesPropertyWidget::pqInternals
{
public:
  std::vector<Node> Nodes; // sorted by value, values unique
  int Current = -1;
  QString Preset; // MaterialPreset: a preset name, or "Custom" (the nodes apply)
  bool HasPresetProperty = false;
  QString CustomPreset = QStringLiteral("Custom"); // MaterialPreset's "use the nodes" value
  int ShownParameter = mmv::Diffuse; // parameter whose curve the track draws

  bool HasDataRange = false;
  double DataRange[2] = { 0, 1 };
  std::vector<std::pair<double, double>> Opacity; // (value, opacity) points

  vtkNew<vtkMaterialLibrary> Library;
  // Mirror of the nodes, so interpolation matches the renderer's exactly.
  vtkNew<vtkMaterialTransferFunction> Function;
  vtkNew<vtkEventQtSlotConnect> VTKConnect;
  vtkWeakPointer<vtkSMProxy> OpacityProxy;

  pqMaterialNodesTrack* Track = nullptr;
  pqDoubleLineEdit* Value = nullptr;
  pqMaterialParameterSpinBox* Spin[ParameterCount] = {};
  QComboBox* Presets = nullptr;
  QToolButton* Remove = nullptr;
  QLabel* Status = nullptr;
  // Numbers MaterialNodes held that the renderer rejects, as loaded: the
  // editors show a sane stand-in (never a NaN clamped to 1000) and mark it,
  // and the next edit writes the stand-in, never the bad number, back.
  QStringList LoadProblems;
  std::vector<std::pair<int, int>> ProblemCells; // (node, parameter) marked red
  QString Refusal; // the last typed value a spin box refused
  QLabel* Notice = nullptr; // shows LoadProblems or Refusal, in red

  void showNotice()
  {
    QString text = this->Refusal;
    if (!this->LoadProblems.isEmpty())
    {
      text = pqMaterialNodesPropertyWidget::tr(
        "MaterialNodes holds invalid numbers, so the renderer ignores it: %1. The editor shows "
        "stand-ins (red); your next edit applies them.")
               .arg(this->LoadProblems.join("; "));
    }
    this->Notice->setText(text);
    this->Notice->setVisible(!text.isEmpty());
  }
  QGridLayout* Grid = nullptr;
  std::vector<std::pair<QLabel*, QWidget*>> Rows; // Value, then the parameters
  int Columns = 0;                                // label/editor pairs per grid row
  bool Updating = false; // editors being filled from the nodes

  void syncFunction()
  {
    std::vector<double> flat;
    flat.reserve(this->Nodes.size() * Stride);
    for (const Node& n : this->Nodes)
    {
      flat.insert(flat.end(), n.begin(), n.end());
    }
    if (!this->Function->SetNodes(static_cast<int>(flat.size()), flat.data()))
    {
      // Out-of-limit values (typed into a state file, say) are reported by
      // the function; the track then shows the last valid nodes' curve.
      vtkLogF(WARNING, "MaterialNodes holds invalid values; the curve may be stale");
    }
  }

  // The representation shades with MaterialPreset instead of the nodes.
  bool presetActive() const
  {
    return this->HasPresetProperty && !this->Preset.isEmpty() &&
      this->Library->HasPreset(this->Preset.toUtf8().constData());
  }

  // The colour map's range, as the representation spreads a preset over it
  // (vtkPVMultiMaterialVolumeRepresentation::UpdateMapperParameters).
  static void colorMapRange(vtkSMProxy* repr, double range[2])
  {
    range[0] = 0.0;
    range[1] = 1.0;
    vtkSMProxy* lut = repr->GetProperty("LookupTable")
      ? vtkSMPropertyHelper(repr, "LookupTable", true).GetAsProxy()
      : nullptr;
    if (lut && lut->GetProperty("RGBPoints"))
    {
      vtkSMPropertyHelper points(lut, "RGBPoints");
      const unsigned int n = points.GetNumberOfElements();
      if (n >= 4)
      {
        range[0] = points.GetAsDouble(0);
        range[1] = points.GetAsDouble(n - 4);
      }
    }
    if (!(range[1] > range[0]))
    {
      range[1] = range[0] + 1.0;
    }
  }

  // Replaces the nodes by the active preset's, as the renderer applies it,
  // so a node added while a preset shows takes the preset's material there
  // (docs/material-editor.md) instead of whatever the unused nodes hold.
  void takePresetNodes(vtkSMProxy* repr)
  {
    double range[2];
    colorMapRange(repr, range);
    vtkNew<vtkMaterialTransferFunction> preset;
    if (!preset->ApplyPreset(this->Preset.toUtf8().constData(), range[0], range[1]))
    {
      return;
    }
    std::vector<double> flat(static_cast<size_t>(preset->GetSize()) * Stride);
    preset->GetNodes(flat.data());
    this->Nodes.clear();
    for (size_t i = 0; i + Stride <= flat.size(); i += Stride)
    {
      Node n;
      std::copy(flat.begin() + i, flat.begin() + i + Stride, n.begin());
      this->Nodes.push_back(n);
    }
    this->syncFunction();
  }

  // Leaves out nodes at a non-finite value and replaces parameters the
  // renderer rejects (NaN: the default; out of limits: the nearest limit),
  // noting each in LoadProblems / ProblemCells. `nodes` is sorted after.
  void sanitize(std::vector<Node>& nodes)
  {
    this->LoadProblems.clear();
    this->ProblemCells.clear();
    // stable_partition, not remove_if: the nodes left out are reported.
    const auto dropped = std::stable_partition(
      nodes.begin(), nodes.end(), [](const Node& n) { return std::isfinite(n[0]); });
    for (auto it = dropped; it != nodes.end(); ++it)
    {
      this->LoadProblems << pqMaterialNodesPropertyWidget::tr("a node at value %1 is left out")
                              .arg((*it)[0]);
    }
    nodes.erase(dropped, nodes.end());
    std::stable_sort(
      nodes.begin(), nodes.end(), [](const Node& a, const Node& b) { return a[0] < b[0]; });
    for (size_t i = 0; i < nodes.size(); ++i)
    {
      for (int p = 0; p < ParameterCount; ++p)
      {
        double& v = nodes[i][p + 1];
        std::string why;
        if (mmv::IsValidMaterialValue(p, v, &why))
        {
          continue;
        }
        const mmv::MaterialParameterInfo& info = mmv::MaterialParameterTable[p];
        const double shown =
          std::isfinite(v) ? std::min(info.HardMax, std::max(info.HardMin, v)) : info.Default;
        this->LoadProblems << pqMaterialNodesPropertyWidget::tr("node %1: %2; shown as %3")
                                .arg(i + 1)
                                .arg(QString::fromStdString(why))
                                .arg(shown);
        this->ProblemCells.emplace_back(static_cast<int>(i), p);
        v = shown;
      }
    }
  }

  // The load problem of the selected node's parameter `p`, or "".
  QString cellProblem(int p) const
  {
    for (const auto& cell : this->ProblemCells)
    {
      if (cell.first == this->Current && cell.second == p)
      {
        return pqMaterialNodesPropertyWidget::tr(
          "MaterialNodes held an invalid number here (the renderer ignored the list); this "
          "shows a stand-in, written back with your next edit.");
      }
    }
    return QString();
  }

  // Preset whose parameters a node carries (for the handle colour), or null.
  const char* presetOf(const Node& node) const
  {
    for (int i = 0; i < this->Library->GetNumberOfPresets(); ++i)
    {
      const char* name = this->Library->GetPresetName(i);
      double p[ParameterCount];
      if (name && this->Library->GetPreset(name, p) &&
        std::equal(p, p + ParameterCount, node.begin() + 1,
          [](double a, double b) { return std::abs(a - b) <= 1e-9 * (1.0 + std::abs(a)); }))
      {
        return name;
      }
    }
    return nullptr;
  }
};

//-----------------------------------------------------------------------------
int pqMaterialNodesTrack::nodeAt(double x) const
{
  double range[2];
  this->Owner->trackRange(range);
  const auto& nodes = this->Owner->Internals->Nodes;
  int best = -1;
  double bestDistance = Radius + 2;
  for (size_t i = 0; i < nodes.size(); ++i)
  {
    const double d = std::abs(this->toX(nodes[i][0], range) - x);
    if (d <= bestDistance)
    {
      best = static_cast<int>(i);
      bestDistance = d;
    }
  }
  return best;
}

//-----------------------------------------------------------------------------
void pqMaterialNodesTrack::paintEvent(QPaintEvent*)
{
  auto& internals = *this->Owner->Internals;
  double range[2];
  this->Owner->trackRange(range);
  const QPalette& pal = this->palette();
  const QRectF plot = this->plotRect();

  QPainter painter(this);
  painter.setRenderHint(QPainter::Antialiasing, true);
  painter.fillRect(this->rect(), pal.base());

  // Opacity curve, filled, as context: where the volume is visible at all.
  if (internals.Opacity.size() >= 2)
  {
    QPainterPath path;
    path.moveTo(this->toX(internals.Opacity.front().first, range), plot.bottom());
    for (const auto& pt : internals.Opacity)
    {
      path.lineTo(this->toX(pt.first, range), plot.bottom() - pt.second * plot.height());
    }
    path.lineTo(this->toX(internals.Opacity.back().first, range), plot.bottom());
    path.closeSubpath();
    QColor fill = pal.color(QPalette::Highlight);
    fill.setAlpha(50);
    QColor line = fill;
    line.setAlpha(140);
    painter.save();
    painter.setClipRect(plot);
    painter.setPen(QPen(line, 1));
    painter.setBrush(fill);
    painter.drawPath(path);
    painter.restore();
  }

  // A whole-range preset replaces the nodes: show it as a band in its colour
  // and draw the (unused) nodes faintly.
  const bool presetActive = internals.presetActive();
  if (presetActive)
  {
    // Neutral: a preset sets no colour (the caption names it).
    QColor band = pal.color(QPalette::Mid);
    band.setAlpha(90);
    painter.fillRect(plot, band);
  }
  painter.setOpacity(presetActive ? 0.35 : 1.0);

  // The shown parameter as the renderer interpolates it, scaled to its
  // editor range (values above SoftMax are drawn at the top).
  const mmv::MaterialParameterInfo& info = mmv::MaterialParameterTable[internals.ShownParameter];
  if (!internals.Nodes.empty())
  {
    QPainterPath curve;
    const int columns = std::max(2, static_cast<int>(plot.width()));
    for (int c = 0; c <= columns; ++c)
    {
      const double x = plot.left() + plot.width() * c / columns;
      const double v =
        internals.Function->EvaluateParameter(this->toValue(x, range), internals.ShownParameter);
      const double t = std::min(1.0, std::max(0.0, (v - info.SoftMin) / (info.SoftMax - info.SoftMin)));
      const QPointF p(x, plot.bottom() - t * plot.height());
      c == 0 ? curve.moveTo(p) : curve.lineTo(p);
    }
    painter.setPen(QPen(pal.color(QPalette::Text), 1.5));
    painter.setBrush(Qt::NoBrush);
    painter.drawPath(curve);
  }

  QFont small = this->font();
  small.setPointSizeF(std::max(6.0, small.pointSizeF() * 0.85));
  painter.setFont(small);
  QColor dim = pal.color(QPalette::Text);
  dim.setAlpha(150);
  painter.setPen(dim);
  painter.setOpacity(1.0);
  QString caption = internals.Nodes.empty()
    ? pqMaterialNodesPropertyWidget::tr("click to add a material node")
    : QString::fromLatin1(info.Key);
  if (presetActive)
  {
    caption = pqMaterialNodesPropertyWidget::tr("preset \"%1\" on the whole range; edit a node to "
                                                "use the nodes")
                .arg(internals.Preset);
  }
  painter.drawText(plot.adjusted(3, 1, -3, 0), Qt::AlignTop | Qt::AlignLeft | Qt::TextWordWrap,
    caption);

  // Range labels under the handle strip.
  const QRectF labels(plot.left(), this->handleY() + Radius + 2, plot.width(),
    this->height() - this->handleY() - Radius - 2);
  painter.drawText(labels, Qt::AlignLeft | Qt::AlignVCenter, QString::number(range[0], 'g', 4));
  painter.drawText(labels, Qt::AlignRight | Qt::AlignVCenter, QString::number(range[1], 'g', 4));

  // Handles: a guide line through the plot and a disc, in the colour of the
  // preset the node matches (grey otherwise); the selected one is outlined.
  const double hy = this->handleY();
  painter.setOpacity(presetActive ? 0.5 : 1.0);
  for (size_t i = 0; i < internals.Nodes.size(); ++i)
  {
    const Node& node = internals.Nodes[i];
    const double x = this->toX(node[0], range);
    const bool selected = static_cast<int>(i) == internals.Current;
    QColor guide = pal.color(QPalette::Mid);
    painter.setPen(QPen(guide, 1, selected ? Qt::SolidLine : Qt::DotLine));
    painter.drawLine(QPointF(x, plot.top()), QPointF(x, plot.bottom()));

    QColor fill = pal.color(QPalette::Button);
    double rgb[3];
    if (const char* preset = internals.presetOf(node))
    {
      if (internals.Library->GetPresetColor(preset, rgb))
      {
        fill = QColor::fromRgbF(rgb[0], rgb[1], rgb[2]);
      }
    }
    painter.setBrush(fill);
    painter.setPen(selected ? QPen(pal.color(QPalette::Highlight), 2.5)
                            : QPen(pal.color(QPalette::Dark), 1));
    painter.drawEllipse(QPointF(x, hy), Radius, Radius);
  }

  painter.setOpacity(1.0);
  painter.setRenderHint(QPainter::Antialiasing, false);
  painter.setBrush(Qt::NoBrush);
  painter.setPen(this->hasFocus() ? pal.color(QPalette::Highlight) : pal.color(QPalette::Mid));
  painter.drawRect(this->rect().adjusted(0, 0, -1, -1));
}

//-----------------------------------------------------------------------------
void pqMaterialNodesTrack::mousePressEvent(QMouseEvent* event)
{
  if (event->button() != Qt::LeftButton)
  {
    this->QWidget::mousePressEvent(event);
    return;
  }
  // Freeze the range while dragging: it follows the nodes otherwise, and a
  // moving scale under the cursor is unusable.
  this->Owner->trackRange(this->DragRange);
  this->Moved = false;
  this->Pending = false;
  int index = this->nodeAt(event->pos().x());
  if (index < 0)
  {
    const double value = std::min(this->DragRange[1],
      std::max(this->DragRange[0], this->toValue(event->pos().x(), this->DragRange)));
    // Added locally; the release commits add + drag as one undoable change.
    index = this->Owner->insertNode(value, &this->Pending);
  }
  this->Dragging = index;
  this->Owner->setCurrentNode(index);
  event->accept();
}

//-----------------------------------------------------------------------------
void pqMaterialNodesTrack::mouseMoveEvent(QMouseEvent* event)
{
  if (this->Dragging < 0 || !(event->buttons() & Qt::LeftButton))
  {
    return;
  }
  const double value = std::min(this->DragRange[1],
    std::max(this->DragRange[0], this->toValue(event->pos().x(), this->DragRange)));
  this->Owner->moveNode(this->Dragging, value, false);
  this->Moved = true;
  event->accept();
}

//-----------------------------------------------------------------------------
void pqMaterialNodesTrack::mouseReleaseEvent(QMouseEvent* event)
{
  if (event->button() == Qt::LeftButton && this->Dragging >= 0)
  {
    if (this->Moved || this->Pending)
    {
      this->Owner->commitNodes();
    }
    this->Dragging = -1;
    this->Moved = this->Pending = false;
    event->accept();
    return;
  }
  this->QWidget::mouseReleaseEvent(event);
}

//-----------------------------------------------------------------------------
void pqMaterialNodesTrack::keyPressEvent(QKeyEvent* event)
{
  const int current = this->Owner->currentNode();
  switch (event->key())
  {
    case Qt::Key_Delete:
    case Qt::Key_Backspace:
      if (current >= 0)
      {
        this->Owner->removeCurrentNode();
        event->accept();
        return;
      }
      break;
    case Qt::Key_Left:
    case Qt::Key_Right:
    {
      const int n = this->Owner->nodeCount();
      if (n > 0)
      {
        const int step = event->key() == Qt::Key_Left ? -1 : 1;
        const int next = current < 0 ? (step > 0 ? 0 : n - 1) : std::min(n - 1, std::max(0, current + step));
        this->Owner->setCurrentNode(next);
        event->accept();
        return;
      }
      break;
    }
    case Qt::Key_Escape:
      if (current >= 0)
      {
        this->Owner->setCurrentNode(-1);
        event->accept();
        return;
      }
      break;
    default:
      break;
  }
  this->QWidget::keyPressEvent(event);
}

//-----------------------------------------------------------------------------
pqMaterialNodesPropertyWidget::pqMaterialNodesPropertyWidget(
  vtkSMProxy* smproxy, vtkSMProperty* smproperty, QWidget* parentObject)
  : Superclass(smproxy, parentObject)
  , Internals(new pqInternals())
{
  auto& internals = *this->Internals;
  // The track and the form are wider than the label column allows.
  this->setShowLabel(false);

  auto* vbox = new QVBoxLayout(this);
  vbox->setMargin(pqPropertiesPanel::suggestedMargin());
  vbox->setSpacing(pqPropertiesPanel::suggestedVerticalSpacing());

  internals.Track = new pqMaterialNodesTrack(this);
  vbox->addWidget(internals.Track);

  // Preset chooser, selection status and remove button on one row.
  auto* row = new QHBoxLayout();
  row->setSpacing(pqPropertiesPanel::suggestedHorizontalSpacing());
  internals.Presets = new QComboBox(this);
  internals.Presets->setObjectName("Presets");
  internals.Presets->setToolTip(tr("Applies a material preset (shading parameters, not colour: "
                                   "colour comes from the colour map) to the selected node, or to "
                                   "the whole range when no node is selected."));
  internals.Presets->addItem(tr("Apply material preset..."));
  const int swatch = this->style()->pixelMetric(QStyle::PM_SmallIconSize);
  for (int i = 0; i < internals.Library->GetNumberOfPresets(); ++i)
  {
    const char* name = internals.Library->GetPresetName(i);
    double parameters[ParameterCount];
    if (!internals.Library->GetPreset(name, parameters))
    {
      continue;
    }
    internals.Presets->addItem(QIcon(presetSwatch(parameters, swatch)), QString::fromUtf8(name));
    internals.Presets->setItemData(internals.Presets->count() - 1,
      presetDescription(name, parameters), Qt::ToolTipRole);
  }
  row->addWidget(internals.Presets, 1);
  internals.Status = new QLabel(this);
  internals.Status->setObjectName("Status");
  row->addWidget(internals.Status);
  internals.Remove = new QToolButton(this);
  internals.Remove->setObjectName("RemoveNode");
  internals.Remove->setIcon(this->style()->standardIcon(QStyle::SP_DialogDiscardButton));
  internals.Remove->setToolTip(tr("Remove the selected node (Delete)"));
  internals.Remove->setAutoRaise(true);
  row->addWidget(internals.Remove);
  vbox->addLayout(row);
  internals.Notice = new QLabel(this);
  internals.Notice->setObjectName("Notice");
  internals.Notice->setWordWrap(true);
  internals.Notice->setStyleSheet(QStringLiteral("QLabel { color: #d02020; }"));
  internals.Notice->setVisible(false);
  vbox->addWidget(internals.Notice);

  // The selected node: its value and the parameters, two per row.
  internals.Grid = new QGridLayout();
  internals.Grid->setHorizontalSpacing(pqPropertiesPanel::suggestedHorizontalSpacing());
  internals.Grid->setVerticalSpacing(pqPropertiesPanel::suggestedVerticalSpacing());
  internals.Value = new pqDoubleLineEdit(this);
  internals.Value->setObjectName("Value");
  internals.Value->setToolTip(tr("Data value of the selected node"));
  internals.Rows.emplace_back(new QLabel(tr("Value"), this), internals.Value);
  for (int p = 0; p < ParameterCount; ++p)
  {
    const mmv::MaterialParameterInfo& info = mmv::MaterialParameterTable[p];
    auto* spin = new pqMaterialParameterSpinBox(this);
    spin->setObjectName(QString::fromLatin1(info.Key));
    // The spin box accepts everything the renderer accepts; the soft range
    // only sets the step, so typical values are a few clicks apart.
    spin->setRange(info.HardMin, info.HardMax);
    spin->setDecimals(info.SoftMax > 10 ? 1 : 3);
    spin->setSingleStep((info.SoftMax - info.SoftMin) / (info.SoftMax > 10 ? 20.0 : 100.0));
    // Commit on Enter/focus-out/arrows, not on every keystroke: one undo step.
    spin->setKeyboardTracking(false);
    spin->setNormalToolTip(tr("%1 of the selected node (typically %2 to %3, at most %4; "
                              "exponent notation such as 2.5e-1 works)")
                             .arg(parameterLabel(p))
                             .arg(info.SoftMin)
                             .arg(info.SoftMax)
                             .arg(info.HardMax));
    spin->Refused = [&internals](const QString& why) {
      internals.Refusal = why;
      internals.showNotice();
      vtkVLogF(PARAVIEW_LOG_APPLICATION_VERBOSITY(), "%s", why.toUtf8().constData());
    };
    internals.Spin[p] = spin;
    auto* label = new QLabel(editorLabel(p), this);
    label->setBuddy(spin);
    internals.Rows.emplace_back(label, spin);
    QObject::connect(spin, QOverload<double>::of(&QDoubleSpinBox::valueChanged), this,
      &pqMaterialNodesPropertyWidget::onParameterEdited);
  }
  this->layoutEditors(1);
  vbox->addLayout(internals.Grid);

  QObject::connect(internals.Value, &pqDoubleLineEdit::textChangedAndEditingFinished, this,
    &pqMaterialNodesPropertyWidget::onValueEdited);
  QObject::connect(internals.Presets, QOverload<int>::of(&QComboBox::activated), this,
    &pqMaterialNodesPropertyWidget::onPresetActivated);
  QObject::connect(internals.Remove, &QToolButton::clicked, this,
    &pqMaterialNodesPropertyWidget::removeCurrentNode);

  // Links pull the current values into the widget now and keep it in step
  // with undo/redo, Python and state files later.
  this->addPropertyLink(this, "materialNodes", SIGNAL(materialNodesChanged()), smproperty);
  if (vtkSMProperty* preset = smproxy->GetProperty("MaterialPreset"))
  {
    internals.HasPresetProperty = true;
    // The property's default is its "use the nodes" entry.
    auto* svp = vtkSMStringVectorProperty::SafeDownCast(preset);
    if (svp && svp->GetDefaultValue(0))
    {
      internals.CustomPreset = QString::fromUtf8(svp->GetDefaultValue(0));
    }
    this->addPropertyLink(this, "materialPreset", SIGNAL(materialPresetChanged()), preset);
  }

  // The track's range and opacity curve follow the data and the colouring.
  internals.VTKConnect->Connect(
    smproxy, vtkCommand::PropertyModifiedEvent, this, SLOT(updateContext()));
  internals.VTKConnect->Connect(smproxy, vtkCommand::UpdateDataEvent, this, SLOT(updateContext()));
  this->updateContext();
  this->updateEditors();

  vtkVLogF(PARAVIEW_LOG_APPLICATION_VERBOSITY(),
    "pqMaterialNodesPropertyWidget created with %d nodes", this->nodeCount());
}

//-----------------------------------------------------------------------------
pqMaterialNodesPropertyWidget::~pqMaterialNodesPropertyWidget() = default;

//-----------------------------------------------------------------------------
QList<QVariant> pqMaterialNodesPropertyWidget::materialNodes() const
{
  QList<QVariant> values;
  for (const Node& n : this->Internals->Nodes)
  {
    for (double v : n)
    {
      values.push_back(v);
    }
  }
  return values;
}

//-----------------------------------------------------------------------------
void pqMaterialNodesPropertyWidget::setMaterialNodes(const QList<QVariant>& values)
{
  auto& internals = *this->Internals;
  std::vector<double> flat;
  flat.reserve(values.size());
  for (const QVariant& v : values)
  {
    flat.push_back(v.toDouble());
  }
  // States written before emission have 9 numbers a node (e = 0), before
  // anisotropy 8 (g = 0, e = 0); the emission field comes from the table.
  int stride = vtkMaterialTransferFunction::DetectNodeStride(
    static_cast<int>(flat.size()), flat.data());
  stride = stride > 0 ? stride : Stride;
  std::vector<Node> nodes;
  for (size_t i = 0; i + stride <= flat.size(); i += stride)
  {
    Node n;
    for (int k = 0; k < Stride; ++k)
    {
      n[k] = k < stride ? flat[i + k] : mmv::MaterialParameterTable[k - 1].Default;
    }
    nodes.push_back(n);
  }
  internals.sanitize(nodes);
  if (!internals.LoadProblems.isEmpty())
  {
    vtkVLogF(PARAVIEW_LOG_APPLICATION_VERBOSITY(), "MaterialNodes: %d invalid number(s) shown as "
      "stand-ins: %s", static_cast<int>(internals.LoadProblems.size()),
      internals.LoadProblems.join("; ").toUtf8().constData());
  }
  const bool sameCount = nodes.size() == internals.Nodes.size();
  internals.Nodes = std::move(nodes);
  // Keep the selection across value edits (undo of a drag); a different
  // node count means nodes came or went, so the index means nothing.
  if (!sameCount)
  {
    internals.Current = -1;
  }
  internals.syncFunction();
  this->updateEditors();
}

//-----------------------------------------------------------------------------
QString pqMaterialNodesPropertyWidget::materialPreset() const
{
  return this->Internals->Preset;
}

//-----------------------------------------------------------------------------
void pqMaterialNodesPropertyWidget::setMaterialPreset(const QString& name)
{
  this->Internals->Preset = name;
  this->Internals->Track->update();
}

//-----------------------------------------------------------------------------
int pqMaterialNodesPropertyWidget::nodeCount() const
{
  return static_cast<int>(this->Internals->Nodes.size());
}

//-----------------------------------------------------------------------------
int pqMaterialNodesPropertyWidget::currentNode() const
{
  return this->Internals->Current;
}

//-----------------------------------------------------------------------------
QString pqMaterialNodesPropertyWidget::nodesText() const
{
  QString text;
  QTextStream stream(&text);
  for (const Node& n : this->Internals->Nodes)
  {
    stream << n[0] << ":";
    for (int p = 1; p < Stride; ++p)
    {
      stream << " " << n[p];
    }
    stream << "\n";
  }
  return text.trimmed();
}

//-----------------------------------------------------------------------------
void pqMaterialNodesPropertyWidget::trackRange(double range[2]) const
{
  const auto& internals = *this->Internals;
  double lo = internals.HasDataRange ? internals.DataRange[0] : VTK_DOUBLE_MAX;
  double hi = internals.HasDataRange ? internals.DataRange[1] : VTK_DOUBLE_MIN;
  // Nodes outside the data stay reachable.
  for (const Node& n : internals.Nodes)
  {
    lo = std::min(lo, n[0]);
    hi = std::max(hi, n[0]);
  }
  if (!(lo <= hi))
  {
    lo = 0.0;
    hi = 1.0;
  }
  else if (!(hi > lo))
  {
    // One node and no data: centre it in a unit-ish window.
    const double half = std::max(0.5, std::abs(lo) * 0.5);
    lo -= half;
    hi += half;
  }
  range[0] = lo;
  range[1] = hi;
}

//-----------------------------------------------------------------------------
void pqMaterialNodesPropertyWidget::setCurrentNode(int index)
{
  auto& internals = *this->Internals;
  internals.Current = (index >= 0 && index < this->nodeCount()) ? index : -1;
  this->updateEditors();
}

//-----------------------------------------------------------------------------
int pqMaterialNodesPropertyWidget::addNode(double value)
{
  bool changed = false;
  const int index = this->insertNode(value, &changed);
  if (changed)
  {
    this->commitNodes();
  }
  return index;
}

//-----------------------------------------------------------------------------
int pqMaterialNodesPropertyWidget::insertNode(double value, bool* changed)
{
  auto& internals = *this->Internals;
  auto& nodes = internals.Nodes;
  const bool fromPreset = internals.presetActive();
  if (fromPreset)
  {
    // commitNodes() then switches MaterialPreset to Custom.
    internals.takePresetNodes(this->proxy());
  }
  if (changed)
  {
    *changed = fromPreset;
  }
  auto it = std::lower_bound(
    nodes.begin(), nodes.end(), value, [](const Node& n, double v) { return n[0] < v; });
  if (it != nodes.end() && (*it)[0] == value)
  {
    const int existing = static_cast<int>(it - nodes.begin());
    this->setCurrentNode(existing);
    return existing;
  }
  Node node;
  node[0] = value;
  // Interpolating keeps the rendering unchanged until the user edits the
  // new node; with no nodes this yields the table defaults.
  internals.Function->Evaluate(value, node.data() + 1);
  // The offset first: insert() may reallocate, invalidating begin().
  const int index = static_cast<int>(it - nodes.begin());
  nodes.insert(it, node);
  if (changed)
  {
    *changed = true;
  }
  internals.Current = index;
  internals.syncFunction();
  this->updateEditors();
  return index;
}

//-----------------------------------------------------------------------------
void pqMaterialNodesPropertyWidget::removeCurrentNode()
{
  auto& internals = *this->Internals;
  if (internals.Current < 0 || internals.Current >= this->nodeCount())
  {
    return;
  }
  internals.Nodes.erase(internals.Nodes.begin() + internals.Current);
  // Select a neighbour so repeated Delete clears nodes one after another.
  internals.Current = std::min(internals.Current, this->nodeCount() - 1);
  this->commitNodes();
}

//-----------------------------------------------------------------------------
void pqMaterialNodesPropertyWidget::moveNode(int index, double value, bool commit)
{
  auto& internals = *this->Internals;
  auto& nodes = internals.Nodes;
  if (index < 0 || index >= this->nodeCount() || !std::isfinite(value))
  {
    return;
  }
  // Nodes keep their order and distinct values (equal values would merge in
  // vtkMaterialTransferFunction), so a node stops just short of a neighbour.
  double range[2];
  this->trackRange(range);
  const double gap = (range[1] - range[0]) * 1e-4;
  if (index > 0)
  {
    value = std::max(value, nodes[index - 1][0] + gap);
  }
  if (index + 1 < this->nodeCount())
  {
    value = std::min(value, nodes[index + 1][0] - gap);
  }
  nodes[index][0] = value;
  if (commit)
  {
    this->commitNodes();
  }
  else
  {
    internals.syncFunction();
    this->updateEditors();
  }
}

//-----------------------------------------------------------------------------
void pqMaterialNodesPropertyWidget::applyPreset(const QString& name)
{
  auto& internals = *this->Internals;
  const QByteArray key = name.toUtf8();
  double parameters[ParameterCount];
  if (!internals.Library->GetPreset(key.constData(), parameters))
  {
    return;
  }
  if (internals.Current >= 0)
  {
    std::copy(parameters, parameters + ParameterCount, internals.Nodes[internals.Current].begin() + 1);
    this->commitNodes();
    return;
  }
  if (internals.HasPresetProperty)
  {
    // The representation spreads the preset over the colour map's range
    // itself (and keeps it there when the range changes); the nodes stay
    // for when the user goes back to them.
    internals.Preset = name;
    vtkVLogF(
      PARAVIEW_LOG_APPLICATION_VERBOSITY(), "MaterialPreset set to '%s'", key.constData());
    internals.Track->update();
    Q_EMIT this->materialPresetChanged();
    return;
  }
  // Same result as vtkMaterialTransferFunction::ApplyPreset over the range.
  double range[2];
  this->trackRange(range);
  Node lo, hi;
  lo[0] = range[0];
  hi[0] = range[1];
  std::copy(parameters, parameters + ParameterCount, lo.begin() + 1);
  std::copy(parameters, parameters + ParameterCount, hi.begin() + 1);
  internals.Nodes = { lo, hi };
  internals.Current = -1;
  this->commitNodes();
}

//-----------------------------------------------------------------------------
void pqMaterialNodesPropertyWidget::commitNodes()
{
  auto& internals = *this->Internals;
  // What is written now holds only the stand-ins, so nothing is left to flag.
  internals.LoadProblems.clear();
  internals.ProblemCells.clear();
  internals.Refusal.clear();
  internals.syncFunction();
  this->updateEditors();
  vtkVLogF(PARAVIEW_LOG_APPLICATION_VERBOSITY(), "MaterialNodes edited: %d nodes",
    this->nodeCount());
  // The property links turn these into property changes (changeAvailable,
  // then one changeFinished: the panel applies them as one undoable step).
  Q_EMIT this->materialNodesChanged();
  if (internals.presetActive())
  {
    // Editing nodes means using them: a whole-range preset would hide the edit.
    internals.Preset = internals.CustomPreset;
    Q_EMIT this->materialPresetChanged();
  }
}

//-----------------------------------------------------------------------------
void pqMaterialNodesPropertyWidget::onParameterEdited()
{
  auto& internals = *this->Internals;
  if (internals.Updating || internals.Current < 0)
  {
    return;
  }
  for (int p = 0; p < ParameterCount; ++p)
  {
    if (this->sender() == internals.Spin[p])
    {
      internals.Nodes[internals.Current][p + 1] = internals.Spin[p]->value();
      internals.ShownParameter = p; // show the curve being edited
      this->commitNodes();
      return;
    }
  }
}

//-----------------------------------------------------------------------------
void pqMaterialNodesPropertyWidget::onValueEdited()
{
  auto& internals = *this->Internals;
  if (internals.Updating || internals.Current < 0)
  {
    return;
  }
  // Same parser as the spin boxes: "nan" or "inf" would pass toDouble().
  const mmv::NumberText parsed = mmv::ParseNumberText(
    internals.Value->text().toStdString(), -VTK_DOUBLE_MAX, VTK_DOUBLE_MAX);
  if (parsed.State == mmv::NumberTextState::Acceptable)
  {
    this->moveNode(internals.Current, parsed.Value, true);
  }
  else
  {
    internals.Refusal =
      tr("%1 refused: a node's value must be a finite number").arg(internals.Value->text());
    this->updateEditors(); // restore the node's value
  }
}

//-----------------------------------------------------------------------------
void pqMaterialNodesPropertyWidget::onPresetActivated(int index)
{
  auto& internals = *this->Internals;
  if (index > 0)
  {
    this->applyPreset(internals.Presets->itemText(index));
  }
  // The combo is an action menu, not a state: back to its prompt.
  internals.Presets->setCurrentIndex(0);
}

//-----------------------------------------------------------------------------
void pqMaterialNodesPropertyWidget::updateEditors()
{
  auto& internals = *this->Internals;
  const bool selected = internals.Current >= 0 && internals.Current < this->nodeCount();
  const bool prev = internals.Updating;
  internals.Updating = true;
  internals.Value->setEnabled(selected);
  internals.Remove->setEnabled(selected);
  for (int p = 0; p < ParameterCount; ++p)
  {
    internals.Spin[p]->setEnabled(selected);
    // With no selection the editors show the defaults a new node would get.
    internals.Spin[p]->setValue(selected ? internals.Nodes[internals.Current][p + 1]
                                         : mmv::MaterialParameterTable[p].Default);
    internals.Spin[p]->setProblem(selected ? internals.cellProblem(p) : QString());
  }
  internals.showNotice();
  internals.Value->setText(selected
      ? pqDoubleLineEdit::formatDoubleUsingGlobalPrecisionAndNotation(
          internals.Nodes[internals.Current][0])
      : QString());
  internals.Status->setText(selected
      ? tr("%1 / %2").arg(internals.Current + 1).arg(this->nodeCount())
      : tr("%n node(s)", nullptr, this->nodeCount()));
  internals.Updating = prev;
  internals.Track->update();
}

//-----------------------------------------------------------------------------
void pqMaterialNodesPropertyWidget::updateContext()
{
  auto& internals = *this->Internals;
  vtkSMProxy* smproxy = this->proxy();

  // Data range of the coloured array, as the representation sees it.
  internals.HasDataRange = false;
  auto* repr = vtkSMRepresentationProxy::SafeDownCast(smproxy);
  if (repr && smproxy->GetProperty("ColorArrayName"))
  {
    vtkSMPropertyHelper colorArray(smproxy, "ColorArrayName");
    const char* name = colorArray.GetInputArrayNameToProcess();
    vtkPVDataInformation* dataInfo = repr->GetRepresentedDataInformation();
    vtkPVArrayInformation* arrayInfo = (name && *name && dataInfo)
      ? dataInfo->GetArrayInformation(name, colorArray.GetInputArrayAssociation())
      : nullptr;
    if (arrayInfo)
    {
      // Magnitude for vectors, which is what volume mapping uses by default.
      arrayInfo->GetComponentRange(
        arrayInfo->GetNumberOfComponents() == 1 ? 0 : -1, internals.DataRange);
      internals.HasDataRange = validRange(internals.DataRange);
    }
  }
  // No data information yet (or no array): the colour map's range.
  vtkSMProxy* lut = smproxy->GetProperty("LookupTable")
    ? vtkSMPropertyHelper(smproxy, "LookupTable", true).GetAsProxy()
    : nullptr;
  if (!internals.HasDataRange && lut && lut->GetProperty("RGBPoints"))
  {
    vtkSMPropertyHelper points(lut, "RGBPoints");
    const unsigned int n = points.GetNumberOfElements();
    if (n >= 8)
    {
      internals.DataRange[0] = points.GetAsDouble(0);
      internals.DataRange[1] = points.GetAsDouble(n - 4);
      internals.HasDataRange = validRange(internals.DataRange);
    }
  }

  // The opacity function this representation uses; follow it when it changes.
  vtkSMProxy* opacity = smproxy->GetProperty("ScalarOpacityFunction")
    ? vtkSMPropertyHelper(smproxy, "ScalarOpacityFunction", true).GetAsProxy()
    : nullptr;
  if (opacity != internals.OpacityProxy)
  {
    if (internals.OpacityProxy)
    {
      internals.VTKConnect->Disconnect(internals.OpacityProxy);
    }
    internals.OpacityProxy = opacity;
    if (opacity)
    {
      internals.VTKConnect->Connect(
        opacity, vtkCommand::PropertyModifiedEvent, this, SLOT(updateContext()));
    }
  }
  internals.Opacity.clear();
  if (opacity && opacity->GetProperty("Points"))
  {
    // (x, opacity, midpoint, sharpness) per point; midpoint and sharpness
    // are drawn as straight segments, which is close enough for context.
    vtkSMPropertyHelper points(opacity, "Points");
    const unsigned int n = points.GetNumberOfElements();
    for (unsigned int i = 0; i + 3 < n; i += 4)
    {
      internals.Opacity.emplace_back(points.GetAsDouble(i), points.GetAsDouble(i + 1));
    }
  }
  internals.Track->update();
}

//-----------------------------------------------------------------------------
void pqMaterialNodesPropertyWidget::layoutEditors(int columns)
{
  auto& internals = *this->Internals;
  if (columns == internals.Columns)
  {
    return;
  }
  internals.Columns = columns;
  for (auto& row : internals.Rows)
  {
    internals.Grid->removeWidget(row.first);
    internals.Grid->removeWidget(row.second);
  }
  for (int i = 0; i < static_cast<int>(internals.Rows.size()); ++i)
  {
    const int r = i / columns;
    const int c = (i % columns) * 2;
    internals.Grid->addWidget(internals.Rows[i].first, r, c);
    internals.Grid->addWidget(internals.Rows[i].second, r, c + 1);
  }
  for (int c = 0; c < 4; ++c)
  {
    internals.Grid->setColumnStretch(c, (c % 2 == 1 && c < 2 * columns) ? 1 : 0);
  }
}

//-----------------------------------------------------------------------------
void pqMaterialNodesPropertyWidget::resizeEvent(QResizeEvent* event)
{
  // Two label/editor pairs per row where they fit (compact), one in the
  // narrow default Properties panel (no horizontal scrolling).
  auto& internals = *this->Internals;
  int pair = 0;
  for (const auto& row : internals.Rows)
  {
    pair = std::max(pair, row.first->sizeHint().width());
  }
  int editor = 0;
  for (const auto& row : internals.Rows)
  {
    editor = std::max(editor, row.second->minimumSizeHint().width());
  }
  const int spacing = std::max(0, internals.Grid->horizontalSpacing());
  pair += editor + spacing;
  const int available = this->contentsRect().width() - 2 * pqPropertiesPanel::suggestedMargin();
  this->layoutEditors(available >= 2 * pair + spacing ? 2 : 1);
  this->Superclass::resizeEvent(event);
}
