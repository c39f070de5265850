#include "pqMaterialNodesTrack.h"

#include "mmvMaterialNodeModel.h"
#include "pqMaterialNodesPropertyWidget.h"

#include <QKeyEvent>
#include <QMouseEvent>
#include <QPainter>
#include <QPainterPath>

#include <algorithm>
#include <cmath>

using Node = mmv::MaterialNodeModel::Node;

//-----------------------------------------------------------------------------
pqMaterialNodesTrack::pqMaterialNodesTrack(
  pqMaterialNodesPropertyWidget* owner, const mmv::MaterialNodeModel& model)
  : QWidget(owner)
  , Owner(owner)
  , Model(model)
{
  this->setObjectName("Track");
  this->setFocusPolicy(Qt::StrongFocus);
  this->setMouseTracking(false);
  this->setSizePolicy(QSizePolicy::Expanding, QSizePolicy::Fixed);
  this->setToolTip(pqMaterialNodesPropertyWidget::tr(
    "Click to add a material node, drag a node to move it, Delete removes the selected node."));
}

//-----------------------------------------------------------------------------
QRectF pqMaterialNodesTrack::plotRect() const
{
  const int text = this->fontMetrics().height();
  return QRectF(
    Radius + 3, 3, this->width() - 2 * (Radius + 3), this->height() - 3 - text - 2 * Radius - 6);
}

//-----------------------------------------------------------------------------
double pqMaterialNodesTrack::toX(double value, const double range[2]) const
{
  const QRectF r = this->plotRect();
  return r.left() + (value - range[0]) / (range[1] - range[0]) * r.width();
}

//-----------------------------------------------------------------------------
double pqMaterialNodesTrack::toValue(double x, const double range[2]) const
{
  const QRectF r = this->plotRect();
  return range[0] + (x - r.left()) / r.width() * (range[1] - range[0]);
}

//-----------------------------------------------------------------------------
int pqMaterialNodesTrack::nodeAt(double x) const
{
  double range[2];
  this->Owner->trackRange(range);
  const auto& nodes = this->Model.GetNodes();
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
void pqMaterialNodesTrack::paintOpacityCurve(QPainter& painter, const double range[2]) const
{
  if (this->View.Opacity.size() < 2)
  {
    return;
  }
  const QPalette& pal = this->palette();
  const QRectF plot = this->plotRect();
  QPainterPath path;
  path.moveTo(this->toX(this->View.Opacity.front().first, range), plot.bottom());
  for (const auto& pt : this->View.Opacity)
  {
    path.lineTo(this->toX(pt.first, range), plot.bottom() - pt.second * plot.height());
  }
  path.lineTo(this->toX(this->View.Opacity.back().first, range), plot.bottom());
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

//-----------------------------------------------------------------------------
void pqMaterialNodesTrack::paintHandles(QPainter& painter, const double range[2]) const
{
  // A guide line through the plot and a disc, in the colour of the preset
  // the node matches (grey otherwise); the selected one is outlined.
  const auto& nodes = this->Model.GetNodes();
  const QPalette& pal = this->palette();
  const QRectF plot = this->plotRect();
  const double hy = this->handleY();
  for (size_t i = 0; i < nodes.size(); ++i)
  {
    const Node& node = nodes[i];
    const double x = this->toX(node[0], range);
    const bool selected = static_cast<int>(i) == this->Model.GetCurrent();
    QColor guide = pal.color(QPalette::Mid);
    painter.setPen(QPen(guide, 1, selected ? Qt::SolidLine : Qt::DotLine));
    painter.drawLine(QPointF(x, plot.top()), QPointF(x, plot.bottom()));

    QColor fill = pal.color(QPalette::Button);
    double rgb[3];
    if (const char* preset = this->Model.PresetOf(node))
    {
      if (this->Model.GetLibrary()->GetPresetColor(preset, rgb))
      {
        fill = QColor::fromRgbF(rgb[0], rgb[1], rgb[2]);
      }
    }
    painter.setBrush(fill);
    painter.setPen(
      selected ? QPen(pal.color(QPalette::Highlight), 2.5) : QPen(pal.color(QPalette::Dark), 1));
    painter.drawEllipse(QPointF(x, hy), Radius, Radius);
  }
}

//-----------------------------------------------------------------------------
void pqMaterialNodesTrack::paintEvent(QPaintEvent*)
{
  const auto& nodes = this->Model.GetNodes();
  const bool presetActive = !this->View.ActivePreset.isEmpty();
  double range[2];
  this->Owner->trackRange(range);
  const QPalette& pal = this->palette();
  const QRectF plot = this->plotRect();

  QPainter painter(this);
  painter.setRenderHint(QPainter::Antialiasing, true);
  painter.fillRect(this->rect(), pal.base());

  // Opacity curve, filled, as context: where the volume is visible at all.
  this->paintOpacityCurve(painter, range);

  // A whole-range preset replaces the nodes: show it as a band in its colour
  // and draw the (unused) nodes faintly.
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
  const mmv::MaterialParameterInfo& info = mmv::MaterialParameterTable[this->View.ShownParameter];
  if (!nodes.empty())
  {
    QPainterPath curve;
    const int columns = std::max(2, static_cast<int>(plot.width()));
    for (int c = 0; c <= columns; ++c)
    {
      const double x = plot.left() + plot.width() * c / columns;
      const double v =
        this->Model.EvaluateParameter(this->toValue(x, range), this->View.ShownParameter);
      const double t =
        std::min(1.0, std::max(0.0, (v - info.SoftMin) / (info.SoftMax - info.SoftMin)));
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
  QString caption = nodes.empty()
    ? pqMaterialNodesPropertyWidget::tr("click to add a material node")
    : QString::fromLatin1(info.Key);
  if (presetActive)
  {
    caption = pqMaterialNodesPropertyWidget::tr("preset \"%1\" on the whole range; edit a node to "
                                                "use the nodes")
                .arg(this->View.ActivePreset);
  }
  painter.drawText(
    plot.adjusted(3, 1, -3, 0), Qt::AlignTop | Qt::AlignLeft | Qt::TextWordWrap, caption);

  // Range labels under the handle strip.
  const QRectF labels(plot.left(), this->handleY() + Radius + 2, plot.width(),
    this->height() - this->handleY() - Radius - 2);
  painter.drawText(labels, Qt::AlignLeft | Qt::AlignVCenter, QString::number(range[0], 'g', 4));
  painter.drawText(labels, Qt::AlignRight | Qt::AlignVCenter, QString::number(range[1], 'g', 4));

  painter.setOpacity(presetActive ? 0.5 : 1.0);
  this->paintHandles(painter, range);

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
        const int next =
          current < 0 ? (step > 0 ? 0 : n - 1) : std::min(n - 1, std::max(0, current + step));
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
